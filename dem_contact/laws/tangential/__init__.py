"""Tangential contact laws, one file each (see ``laws.table`` for what a law file declares); ``common``
holds the arithmetic that several of them share.

Every planar law receives the normal force after the step N >= 0 [N], its increment dN [N], the contact
radius after and before the step a, a_old [m], and the tangential displacement increment dd = v_t dt [m]
of the contact patch. It returns T [N], the tangential force in the direction of positive displacement
(the force on body 1 is -T), and updates its history slots in place. Every law caps |T| <= mu N. When
N <= 0 or a <= 0 the contact carries no tangential load: history is released.

The 3D form (``vector``) acts on vectors of the tangent plane (``laws.vector``): it reads N and a of the
last step from the row's header and writes its own slots from the tangential base b; slot b holds the
running work 0.5 (T_old + T) . dd.
"""
