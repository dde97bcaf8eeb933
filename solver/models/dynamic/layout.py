"""Layout of the dynamic model's state vector and per-contact result record, and the integer mode
constants of its parameter record.

The state and the per-contact record are flat float64 arrays (the integrator works on the state
vector as a whole) whose slots are named here. The parameters are a named record,
:class:`solver.models.dynamic.params.ModelParams`.

State vector ``y`` (SI units, inertial frame of case-format.md: x = bearing axis, gravity along -z;
origin = outer-ring centre on the plane of the ball centres in the just-touching reference state):

- ball j, 13 slots from ``ball_base(j) = BALL_STRIDE * j``:
  ``B_POS`` (3) centre position [m], ``B_VEL`` (3) centre velocity [m/s],
  ``B_QUAT`` (4) unit quaternion [w, x, y, z] rotating ball-fixed components into inertial ones,
  ``B_OMEGA`` (3) angular velocity, inertial components [rad/s];
- inner ring, 12 slots from ``ring_base(Z)``: ``R_POS`` (3) centre offset from the just-touching
  position [m], ``R_VEL`` (3) [m/s], ``R_TILT`` (2) small-rotation tilt vector (about y, z) [rad],
  ``R_TILT_RATE`` (2) [rad/s], ``R_PHI_INNER`` spin angle of the inner ring [rad],
  ``R_PHI_OUTER`` spin angle of the outer ring [rad];
- cage, 12 slots from ``cage_base(Z)``: ``C_POS`` (3) centre [m], ``C_VEL`` (3) [m/s],
  ``C_ANGLE`` rotation about its own axis [rad], ``C_SPEED`` angular speed about it [rad/s],
  ``C_TILT`` (2) small-rotation tilt vector about y, z [rad], ``C_TILT_RATE`` (2) [rad/s]: 6 DOF.
  Cage orientation R = R(tilt) R_x(angle). The guiding land acts on the cage centre (no tilt
  moment from the land).
"""

from __future__ import annotations

# ---- state: ball block --------------------------------------------------------------------------
BALL_STRIDE = 13
B_POS = 0
B_VEL = 3
B_QUAT = 6
B_OMEGA = 10

# ---- state: inner-ring block (offsets from ring_base) -----------------------------------------
RING_SIZE = 12
R_POS = 0
R_VEL = 3
R_TILT = 6
R_TILT_RATE = 8
R_PHI_INNER = 10
R_PHI_OUTER = 11

# ---- state: cage block (offsets from cage_base) -------------------------------------------------
CAGE_SIZE = 12
C_POS = 0
C_VEL = 3
C_ANGLE = 6
C_SPEED = 7
C_TILT = 8
C_TILT_RATE = 10


def ball_base(j: int) -> int:
    """First slot of ball ``j``."""
    return BALL_STRIDE * j


def ring_base(ball_count: int) -> int:
    """First slot of the inner-ring block."""
    return BALL_STRIDE * ball_count


def cage_base(ball_count: int) -> int:
    """First slot of the cage block."""
    return BALL_STRIDE * ball_count + RING_SIZE


def state_size(ball_count: int) -> int:
    """Length of the state vector."""
    return BALL_STRIDE * ball_count + RING_SIZE + CAGE_SIZE


# ---- integer mode constants of the parameter record (solver.models.dynamic.params.ModelParams) --
# tilt_mode: how the inner ring's misalignment enters
TILT_FIXED_IN_SPACE = 0  # imposed tilt fixed in space (housing/shaft misalignment)
TILT_TURNING_WITH_RING = 1  # imposed tilt turning with the ring (rotating runout)
TILT_FREE = 2  # tilts are degrees of freedom under an applied moment
# guidance: which surface guides the cage
GUIDE_OUTER_RING = 0
GUIDE_INNER_RING = 1
GUIDE_BALL = 2

# ---- per-contact record written by the contact kernel -------------------------------------------
K_F_BALL = 0  # force on the ball, inertial (3) [N]
K_M_BALL = 3  # moment on the ball about its centre (3) [N m]
K_F_RING = 6  # force on the ring (3) [N]
K_M_RING = 9  # moment on the ring about the ring centre (3) [N m]
K_LOAD = 12  # normal load Q (elastic + damping, >= 0) [N]
K_DEFLECTION = 13  # elastic approach delta (may be negative: gap) [m]
K_ANGLE = 14  # contact angle in the ring's meridian plane [rad]
K_AZIMUTH = 15  # ring-frame azimuth of the contact centre [rad]
K_POINT = 16  # contact centre, ring frame (3) [m]
K_NORMAL = 19  # unit vector from ball centre to contact, inertial (3)
K_SEMI_MAJOR = 22  # a [m]
K_SEMI_MINOR = 23  # b [m]
K_PMAX = 24  # peak pressure [Pa]
K_SPIN = 25  # spin component of ball-minus-ring angular velocity along u(alpha) [rad/s]
K_ROLL = 26  # rolling component [rad/s]
K_SLIDE = 27  # sliding speed at the contact centre [m/s]
K_ENTRAIN = 28  # entrainment (mean rolling) speed [m/s]
K_RX = 29  # equivalent radius in the rolling direction [m]
K_RY = 30  # equivalent radius across the groove [m]
K_ELASTIC = 31  # elastic part of Q, K delta^1.5 [N]
K_FILM = 32  # central EHL film thickness, inlet shear heating included [m]
K_POWER_ROLLING = 33  # power of the rolling resistance (EHL inlet + hysteresis) [W]
K_POWER_SLIDING = 34  # traction power from the slip at the contact centre [W]
K_POWER_SPIN = 35  # traction power from the relative rotation (spin, differential slip) [W]
# filled by the observation step (observe.py) for the output samples only
K_LATITUDE = 36  # latitude of the contact on the ball [rad]
K_LONGITUDE = 37  # longitude of the contact on the ball [rad]
K_SPIN_TO_ROLL = 38  # K_SPIN / K_ROLL (0 when not rolling)
N_CONTACT_RECORD = 39

# ---- per-ball and bearing-level records of the observation step (observe.py) -------------------
BO_POCKET_FORCE = 0  # pocket normal force [N]
BO_POCKET_POWER = 1  # power dissipated in the ball-pocket contact [W]
BO_DRAG_POWER = 2  # power of the oil-air drag on the ball [W]
N_BALL_OUTPUT = 3
RO_LAND_POWER = 0  # power dissipated at the cage-guiding land [W]
RO_FRICTION_TORQUE = 1  # torque needed to turn the inner ring at its speed [N m]
RO_DRIVE_POWER = 2  # power fed in by the imposed ring rotations [W]
RO_CAGE_DRAG_POWER = 3  # power of the oil-air drag on the cage [W]
RO_ELASTIC_ENERGY = 4  # elastic (Hertz) energy of the ball-race contacts, 2/5 Q delta each [J]
N_BEARING_OUTPUT = 5
