"""Normal contact laws, one file each (see ``laws.table`` for what a law file declares)."""
