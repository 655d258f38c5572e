"""The process itself: kernel loading, Ctrl+C, thread priority and memory tuning."""
