"""Contact laws: jitted kernels (``normal``, ``tangential``), their dispatch (``contact``) and the named
slots of the parameter and history rows (``slots``)."""
