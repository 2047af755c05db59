"""What a DEM code calls: 3D per-contact and batch kernels (``contact3d``), parameter tables for many
materials (``pairs``) and the contacts of spheres with walls for the batch kernels (``walls``, on the wall
kinds of ``dem_contact.walls``). Uses ``laws``, ``walls`` and the materials only."""
