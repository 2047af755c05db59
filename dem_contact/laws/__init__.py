"""Contact laws: one file per law in the folder of its family (``normal/``, ``tangential/``, ``twist/``,
``rolling/``), listed in ``table``; the switch on law ids (``dispatch``, generated from the table); the
planar contact step (``contact``); the named slots of the parameter and history rows (``slots``) and the
3D layout (``vector``); closed forms (``closed_forms``); and the contact model of a pair of bodies with
its calibration (``model``: ``Scene``; ``normal_impact``)."""
