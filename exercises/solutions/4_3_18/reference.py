"""4.3.18, the textbook's program (Figs. 4.166-4.175): axes driven by set-points, put-in and take-out by steps.

Per axis (X shown; Y with y1..y6 -> 1.0..6.0 and Z with z1..z3 -> 1.0..3.0 alike):
Fb1 writes the actual position 1.0, 2.0, 3.0 while a position sensor is on; Fb2 says "on a sensor";
Fb3, on leaving a sensor (N edge), moves the actual position half a step in the remembered direction
(0.5 left of x1, 1.5 between x1 and x2 ...); Ax drives toward the set-point and remembers the direction.
Steps: S0 a request's rising edge starts; S1 Z to the middle (2.0); S2 X to DATA.x and Y to 2*DATA.y
(put-in, above the shelf) or 2*DATA.y - 1 (take-out, below it); S3 Z forward (3.0); S4 Y to the opposite
sensor of the row (puts the part down / lifts it); S5 Z back to the middle, then both requests are cleared;
S6 the end. The DBs' set-point start values are 1.0, so the crane goes to [1,1] with the fork back (z1)
when it is switched on.
"""


def x_position(t):
    """Fb1 (4.166) for X: on a sensor, the actual position is the sensor's number."""
    if t.x1:
        t.OS_X.aktualna = 1.0  # MOVE
    if t.x2:
        t.OS_X.aktualna = 2.0  # MOVE
    if t.x3:
        t.OS_X.aktualna = 3.0  # MOVE


def x_on_sensor(t):
    """Fb2 (4.167) for X."""
    t.OS_X.na_snimaci = t.x1 or t.x2 or t.x3


def x_between(t):
    """Fb3 (4.168) for X: leaving a sensor, half a step in the direction of the last motion."""
    if N(t.OS_X.na_snimaci, "OS_X.na_snimaci_sb"):
        if t.OS_X.bol_pohyb_vpravo:
            t.OS_X.aktualna = t.OS_X.aktualna + 0.5  # ADD
        if t.OS_X.bol_pohyb_vlavo:
            t.OS_X.aktualna = t.OS_X.aktualna - 0.5  # SUB


def x_drive(t):
    """Ax (4.169) for X: toward the set-point; the direction is remembered."""
    if t.OS_X.ziadana > t.OS_X.aktualna:
        t.x_vpravo = True
        t.OS_X.bol_pohyb_vpravo = True  # S
        t.OS_X.bol_pohyb_vlavo = False  # R
    else:
        t.x_vpravo = False
    if t.OS_X.ziadana < t.OS_X.aktualna:
        t.x_vlavo = True
        t.OS_X.bol_pohyb_vlavo = True  # S
        t.OS_X.bol_pohyb_vpravo = False  # R
    else:
        t.x_vlavo = False


def y_position(t):
    """Fb1 for Y: y1..y6 -> 1.0..6.0."""
    if t.y1:
        t.OS_Y.aktualna = 1.0
    if t.y2:
        t.OS_Y.aktualna = 2.0
    if t.y3:
        t.OS_Y.aktualna = 3.0
    if t.y4:
        t.OS_Y.aktualna = 4.0
    if t.y5:
        t.OS_Y.aktualna = 5.0
    if t.y6:
        t.OS_Y.aktualna = 6.0


def y_on_sensor(t):
    """Fb2 for Y."""
    t.OS_Y.na_snimaci = t.y1 or t.y2 or t.y3 or t.y4 or t.y5 or t.y6


def y_between(t):
    """Fb3 for Y."""
    if N(t.OS_Y.na_snimaci, "OS_Y.na_snimaci_sb"):
        if t.OS_Y.bol_pohyb_hore:
            t.OS_Y.aktualna = t.OS_Y.aktualna + 0.5
        if t.OS_Y.bol_pohyb_dole:
            t.OS_Y.aktualna = t.OS_Y.aktualna - 0.5


def y_drive(t):
    """Ax for Y."""
    if t.OS_Y.ziadana > t.OS_Y.aktualna:
        t.y_hore = True
        t.OS_Y.bol_pohyb_hore = True
        t.OS_Y.bol_pohyb_dole = False
    else:
        t.y_hore = False
    if t.OS_Y.ziadana < t.OS_Y.aktualna:
        t.y_dole = True
        t.OS_Y.bol_pohyb_dole = True
        t.OS_Y.bol_pohyb_hore = False
    else:
        t.y_dole = False


def z_position(t):
    """Fb1 for Z: z1 back, z2 middle, z3 forward -> 1.0..3.0."""
    if t.z1:
        t.OS_Z.aktualna = 1.0
    if t.z2:
        t.OS_Z.aktualna = 2.0
    if t.z3:
        t.OS_Z.aktualna = 3.0


def z_on_sensor(t):
    """Fb2 for Z."""
    t.OS_Z.na_snimaci = t.z1 or t.z2 or t.z3


def z_between(t):
    """Fb3 for Z."""
    if N(t.OS_Z.na_snimaci, "OS_Z.na_snimaci_sb"):
        if t.OS_Z.bol_pohyb_vpred:
            t.OS_Z.aktualna = t.OS_Z.aktualna + 0.5
        if t.OS_Z.bol_pohyb_vzad:
            t.OS_Z.aktualna = t.OS_Z.aktualna - 0.5


def z_drive(t):
    """Ax for Z."""
    if t.OS_Z.ziadana > t.OS_Z.aktualna:
        t.z_vpred = True
        t.OS_Z.bol_pohyb_vpred = True
        t.OS_Z.bol_pohyb_vzad = False
    else:
        t.z_vpred = False
    if t.OS_Z.ziadana < t.OS_Z.aktualna:
        t.z_vzad = True
        t.OS_Z.bol_pohyb_vzad = True
        t.OS_Z.bol_pohyb_vpred = False
    else:
        t.z_vzad = False


def s0_request(t):
    """S0 (4.170): the rising edge of either request starts the sequence."""
    if P(t.DATA.Poziadavka_naloz, "DATA.Poziadavka_naloz_sb"):
        t.DATA.KROK = 1
    if P(t.DATA.Poziadavka_vyloz, "DATA.Poziadavka_vyloz_sb"):
        t.DATA.KROK = 1


def s1_z_middle(t):
    """S1 (4.171): the fork to the middle (transport) position."""
    if t.DATA.KROK == 1:
        t.OS_Z.ziadana = 2.0
        if t.OS_Z.aktualna == 2.0:
            t.DATA.KROK = 2


def s2_x_y_target(t):
    """S2 (4.172): X to the column, Y above the shelf (put-in: 2y) or below it (take-out: 2y - 1)."""
    if t.DATA.KROK == 2:
        t.OS_X.ziadana = t.DATA.x
        if t.DATA.Poziadavka_naloz:
            t.OS_Y.ziadana = 2.0 * t.DATA.y  # MUL
        if t.DATA.Poziadavka_vyloz:
            t.OS_Y.ziadana = 2.0 * t.DATA.y - 1.0  # MUL, SUB
        if t.OS_X.aktualna == t.OS_X.ziadana and t.OS_Y.aktualna == t.OS_Y.ziadana:
            t.DATA.KROK = 3


def s3_z_forward(t):
    """S3 (4.173): the fork forward into the rack."""
    if t.DATA.KROK == 3:
        t.OS_Z.ziadana = 3.0
        if t.OS_Z.aktualna == 3.0:
            t.DATA.KROK = 4


def s4_y_opposite(t):
    """S4 (4.174): Y to the row's other sensor: down (puts the part on the shelf) or up (lifts it)."""
    if t.DATA.KROK == 4:
        if t.DATA.Poziadavka_naloz:
            t.OS_Y.ziadana = 2.0 * t.DATA.y - 1.0
        if t.DATA.Poziadavka_vyloz:
            t.OS_Y.ziadana = 2.0 * t.DATA.y
        if t.OS_Y.aktualna == t.OS_Y.ziadana:
            t.DATA.KROK = 5


def s5_z_back(t):
    """S5 (4.175): the fork back to the middle; then the requests are cleared."""
    if t.DATA.KROK == 5:
        t.OS_Z.ziadana = 2.0
        if t.OS_Z.aktualna == 2.0:
            t.DATA.KROK = 6
            t.DATA.Poziadavka_naloz = False  # R
            t.DATA.Poziadavka_vyloz = False  # R


OB1 = [
    x_position,
    x_on_sensor,
    x_between,
    x_drive,
    y_position,
    y_on_sensor,
    y_between,
    y_drive,
    z_position,
    z_on_sensor,
    z_between,
    z_drive,
    s0_request,
    s1_z_middle,
    s2_x_y_target,
    s3_z_forward,
    s4_y_opposite,
    s5_z_back,
]
