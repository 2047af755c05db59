"""What a DEM code calls: 3D per-contact and batch kernels (``contact3d``) and parameter tables for many
materials (``pairs``). Uses ``laws`` and the materials only."""
