#!/usr/bin/python3
"""Independent reference for `simulate` on a shaft with ANISOTROPIC bearings (docs/model.md §18.19).

usage: shaft_aniso_reference.py STABILITY_SCAN [SCENE]

SCENE defaults to tests/scenes/shaft/aniso_four_elements.toml (four elements, two viscous balls,
two anisotropic bearings). The program integrates the shaft in the frame ROTATING with it, where
an anisotropic bearing's force turns at twice the spin angle (model.md (18.19.2)); this script
integrates the same machine in the FIXED frame, where the bearing is the constant spring and
damper -K_f U - C_f U' on the node's fixed-frame translation U: shaft_simulation_reference.py's
own Lagrangian (exact sympy element matrices, the balls as point masses, the isotropic spin term)
with K_f, C_f assembled as they are written in the scene — no rotation, no mean and deviator.
scipy's DOP853 at rtol 1e-11 (the shaft is not stiff here, stiffness ratio 0.004; DOP853 meets
Radau to 1e-13 (L + |q|) and takes a seventh of its time); the balancer node's translation is turned into the rotating frame,
q = R(-theta) z_b, beta_i = alpha_i - theta, and compared with the program's rk8pd run at rtol
1e-10 over 0.025 s (51 samples), at constant speed and on the ramp omega/2 -> omega at 30 omega/s
(a restart at t = 1/60 s, where theta must carry on):
    |q_prog - q_ref| <= 1e-8 (L + |q|),   |beta_prog - beta_ref| <= 1e-8 rad,
the tolerance of shaft_simulation_reference.py and for the same reasons (the program's global
error ~8 rtol of the scaled size, the reference's a few 1e-11, a factor ~10 for the growth over
the run). The check sees the anisotropy's direction: reversing the sign of the bearings'
stiffness_xy moves the reference by 0.24 (L + |q|) on q and 1e-3 rad on beta.
Exit 0 if both runs agree, 1 otherwise.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from shaft_simulation_reference import compare  # noqa: E402

if __name__ == '__main__':
    here = os.path.dirname(os.path.abspath(__file__))
    scene = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, '..', 'scenes', 'shaft', 'aniso_four_elements.toml')
    with tempfile.TemporaryDirectory() as work:
        sys.exit(compare(sys.argv[1], scene, work, method='DOP853'))
