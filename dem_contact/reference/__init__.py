"""Slow exact references that judge the fast laws: the boundary-element solution of the tangential contact
of spheres (``bem``) and the named loading paths used to compare laws with it (``paths``)."""
