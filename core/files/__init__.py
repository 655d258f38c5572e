"""Files: the checked-JSON reader, scene, mesh and lesson files, and writes that are whole or absent."""
