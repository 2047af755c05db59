"""Rebound kinematics as pure functions of numbers: the Wu, Thornton & Li (2009) model, the bilinear and
rigid-body models (``models``) and the eq. 4.5 fit (``fit``). Nothing here integrates an impact."""
