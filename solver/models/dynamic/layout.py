"""Layout of the dynamic model's state vector, parameter vector and per-contact result record.

Everything the numba kernels exchange is a flat float64 array whose slots are named here, so the
kernels never take long positional tuples and every slot is documented in one place.

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


# ---- parameter vector ---------------------------------------------------------------------------
# Every entry SI. Flags are stored as 0.0/1.0.
P_Z = 0  # ball count
P_D = 1  # ball diameter [m]
P_DM = 2  # pitch diameter [m]
P_MB = 3  # ball mass [kg]
P_JB = 4  # ball polar inertia [kg m^2]
P_RI = 5  # inner groove radius r_i [m]
P_RO = 6  # outer groove radius r_o [m]
P_XCI = 7  # inner groove curvature-centre axial position, ring frame [m]
P_RCI = 8  # inner groove curvature-centre circle radius [m]
P_XCO = 9  # outer groove curvature-centre axial position [m]
P_RCO = 10  # outer groove curvature-centre circle radius [m]
P_FI = 11  # inner conformity f_i
P_FO = 12  # outer conformity f_o
P_EPRIME = 13  # effective modulus E' [Pa]
P_WI = 14  # inner ring speed [rad/s]
P_WO = 15  # outer ring speed [rad/s]
P_MR = 16  # inner ring (+ shaft share) mass [kg]
P_IRD = 17  # inner ring diametral inertia [kg m^2]
P_IRP = 18  # inner ring polar inertia [kg m^2]
P_FX = 19  # applied force on the inner ring, x [N]
P_FY = 20  # y [N]
P_FZ = 21  # z [N]
P_MY = 22  # applied moment on the inner ring about y [N m]
P_MZ = 23  # about z [N m]
P_TILT_MODE = 24  # 0 imposed tilt fixed in space, 1 imposed tilt turning with the ring, 2 tilt DOF
P_TILT_Y = 25  # imposed tilt vector, y component [rad]
P_TILT_Z = 26  # imposed tilt vector, z component [rad]
P_RING_FREE = 27  # 1: ring translations are DOF; 0: ring held at its initial position
P_GRAVITY = 28  # gravitational acceleration along -z [m/s^2]
P_ZETA = 29  # ball-race contact damping ratio (0 = none)
P_TRACTION = 30  # 1: ellipse-integrated traction on; 0: frictionless contacts
P_MU_A = 31  # traction curve mu(u) = (A + B u) exp(-C u) + D
P_MU_B = 32
P_MU_C = 33
P_MU_D = 34
P_CAGE_ON = 35  # 1: cage modelled
P_MC = 36  # cage mass [kg]
P_IC = 37  # cage polar inertia [kg m^2]
P_CAGE_R = 38  # pocket-centre radius in the cage [m]
P_CP = 39  # pocket diametral clearance [m]
P_KP = 40  # pocket contact stiffness (linear) [N/m]
P_ZETA_P = 41  # pocket contact damping ratio
P_MU_P = 42  # ball-pocket friction coefficient
P_GUIDE = 43  # cage guidance: 0 outer ring land, 1 inner ring land, 2 ball-guided
P_RG = 44  # guiding land radius [m]
P_CG = 45  # guiding radial clearance [m]
P_LG = 46  # guiding land width [m]
P_ETA = 47  # lubricant dynamic viscosity [Pa s]
P_KG = 48  # cage-land metal contact stiffness [N/m]
P_MU_G = 49  # cage-land metal contact friction coefficient
P_V_REG = 50  # regularisation speed of Coulomb friction (tanh) [m/s]
P_HEATHCOTE = 51  # 1: evaluate slip on the curved (deformed) ellipse surface
P_POCKET_BLOCK = 52  # start of the pocket parameter array of solver.physics.cage_contact (9 slots)
P_LAND_BLOCK = 61  # start of the land parameter array of solver.physics.cage_contact (14 slots)
P_ICD = 75  # cage diametral inertia [kg m^2]
N_PARAMS = 76

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
N_CONTACT_RECORD = 32
