"""Files: the checked-JSON reader (scene and lesson files are read by it), scene and mesh files, and writes
that are whole or absent (lesson files: core.lessons.lesson_file)."""
