"""Lessons in the window: applying a step, recording one, checking facts and asking exercises."""
