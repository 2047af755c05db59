"""Contact laws: jitted kernels (``normal``, ``tangential``, ``mdr``), their dispatch (``contact``), the
named slots of the parameter and history rows (``slots``), closed forms (``closed_forms``), and the
contact model of a pair of bodies with its calibration (``model``: ``Scene``; ``normal_impact``)."""
