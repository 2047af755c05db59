"""Studies built on impacts: the published cases of Wu et al. 2009 (``wu2009``), the Chung & Ooi suite
(``chung_ooi``), the speed-accuracy chart (``chart``), the stability map (``stability``) and model advice
(``advise``)."""
