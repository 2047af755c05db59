"""The oblique impact of a sphere on a wall or a second sphere: the integrator kernel, the single-impact
API and result (``impact``), parallel sweeps (``sweep``) and the published scenes (``presets``)."""
