"""The package's version (also in pyproject.toml): written into the files it makes for other programs (the
LAMMPS plugin's table files), which refuse those of another version."""

__version__ = "0.1.0"
