#!/usr/bin/python3
"""Rotor - housing - ball autobalancer with a variable spin speed, derived with SymPy.

Run with Debian's interpreter:  /usr/bin/python3 tools/derive/derive_rotor.py [options]

  (no option)       derive, run every check, print the equations (sympy pretty print)
  --latex           print the equations as LaTeX instead
  --write-json F    also write the numeric check values to F (tools/derive/check_values.json)
  --check-json F    compare the numeric check values with F (relative 1e-12); exit 1 if they differ
  --quiet           do not print the equations

Model (docs/rotor.md, docs/device.md): rotor-housing coordinates q = (x, y, alpha, beta) (small),
the rotor angle phi_0 (spin rate Omega = phi_0', Omega' = phi_0''), the balls' absolute angles
phi_ji (plane j, ball i); the unbalance of plane j is a point mass m_j0 at radius r_j0 carried by
the rotor at the angle phi_0 + psi_j0.  Planes are data (PLANES_*), one code path for any number.

What is derived here, and how:
 1. The kinetic energy of one point mass on a track of the tilted balancer plane and of the
    spinning rotor are computed EXACTLY (rotation matrix R_x(alpha) R_y(beta) [R_z(phi_0)], the
    Resal angles of the paper: first alpha about x, then beta about the new y) and expanded in a
    bookkeeping parameter eps that scales the rotor coordinates.  The model kinetic energy keeps
      - rotor-housing terms to order eps^2 (M, A, the spin energy 1/2 J Omega^2, the gyroscopic
        term C Omega alpha' beta);
      - terms carrying a ball or unbalance mass to order eps^1 (the balls' own energy and the
        coupling with the motion of the balancer centre D).
    DROPPED (assumptions (2.2), printed by the script): every term of order eps^2 that carries a
    small mass (the small masses' translational energy 1/2 m (u_D'^2 + v_D'^2), i.e. the paper's
    "the balls do not enter M and A", and the tilt corrections of the ball positions), every
    rotor-housing term of order eps^3 and higher (e.g. 1/2 C alpha'^2 beta^2), the axial motion z
    (it decouples, (2.12)).  In the phi_0 equation this removes the products of two small rotor
    coordinates with a small mass (e.g. d/dt of m_0 (u_D'^2 + v_D'^2) terms do not arise) but
    KEEPS the vibration torque m_j0 r_j0 (-u_D'' sin + v_D'' cos) (first order in the rotor
    coordinates times a small mass: the Sommerfeld effect) and the gyroscopic reaction
    C (alpha' beta)' (same order; it is the partner of the term C Omega' beta of the alpha
    equation and both are needed for the energy balance).
    The motor's rotor (inertia J - C_p) spins about the same axis but is mounted on the frame
    (torsionally rigid, laterally flexible coupling): it adds 1/2 (J - C_p) Omega^2 and no
    gyroscopic term, so the gyroscopic coefficient stays C = C_p as in (3.2).
 2. Potential energy and Rayleigh function of the individual supports (left at z = -l_L, right at
    z = +l_R, a body point at axial coordinate p moves by (x + p beta, y - p alpha)), the balls'
    viscous resistance 1/2 h r^2 (phi_i' - Omega)^2 (it acts on the ball and, with the opposite
    sign, on the rotor), the motor torque L(Omega) and the resistance torque k_r Omega
    (generalized forces on phi_0).
 3. Lagrange's equations; (a) prescribed speed: phi_0(t) given, equations for q and the balls;
    (b) motor: phi_0 a degree of freedom with its own equation.
Checks (each raises AssertionError when it fails):
 (a) Omega constant: the equations are exactly (3.2)/(3.4) [(3.5)-(3.8) for two planes] of
     docs/rotor.md, written out independently below with the lumped coefficients (2.9), (2.11);
 (a') Omega variable: the derived equations are (3.2)/(3.4) with omega -> Omega(t) and the unbalance
     carried at phi_0(t) + psi_0, plus exactly one term, C Omega' beta in the alpha equation;
 (b) the rotating-frame ball equation (psi = phi - phi_0) with the Euler terms follows
     identically from the fixed-frame one for a general phi_0(t);
 (c) the energy balance dE/dt = P_drive - D holds identically along the equations (symbolic:
     dE/dt - P + D is a combination of the equation residuals) and numerically at the check state.
"""
import argparse
import json
import sys

import sympy as sp

t = sp.Symbol('t', real=True)
eps = sp.Symbol('epsilon', positive=True)

# ----------------------------------------------------------------------------------------------
# Parameters (symbols)
M_k, A_k, m_p, A_p, C_p, J = sp.symbols('M_k A_k m_p A_p C_p J', positive=True)
l_L, l_R = sp.symbols('l_L l_R', positive=True)
c_Lx, c_Ly, c_Rx, c_Ry = sp.symbols('c_Lx c_Ly c_Rx c_Ry', nonnegative=True)
h_Lx, h_Ly, h_Rx, h_Ry = sp.symbols('h_Lx h_Ly h_Rx h_Ry', nonnegative=True)
k_r = sp.Symbol('k_r', nonnegative=True)
Lfun = sp.Function('L')          # motor characteristic L(Omega)

# Rotor coordinates and the rotor angle
x, y, al, be, ph0 = [sp.Function(n, real=True)(t) for n in ('x', 'y', 'alpha', 'beta', 'phi_0')]
Om = ph0.diff(t)
q_rotor = [x, y, al, be]


def rot_x(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def rot_y(b):
    return sp.Matrix([[sp.cos(b), 0, sp.sin(b)], [0, 1, 0], [-sp.sin(b), 0, sp.cos(b)]])


def rot_z(c):
    return sp.Matrix([[sp.cos(c), -sp.sin(c), 0], [sp.sin(c), sp.cos(c), 0], [0, 0, 1]])


def scale_eps(expr):
    """Scale the rotor coordinates by eps (bookkeeping of the small-motion assumption)."""
    return expr.subs({x: eps * x, y: eps * y, al: eps * al, be: eps * be}, simultaneous=True)


def eps_part(expr, order):
    """Coefficient of eps^order of expr (a polynomial after series expansion)."""
    # Taylor coefficient by differentiation (sympy's series() mishandles some products of
    # derivatives of functions of t here: it lost a term in sympy 1.11)
    return sp.expand(expr.diff(eps, order).subs(eps, 0) / sp.factorial(order))


# ----------------------------------------------------------------------------------------------
# 1. Exact kinetic energies and their truncation


def point_mass_energy_parts(m, r, d, ang, orders=3):
    """Exact kinetic energy of a point mass m at radius r, angle ang (absolute, measured in the
    tilted non-spinning axes of the balancer plane z = d), split in orders eps^0, eps^1, eps^2
    (the first `orders` of them: derive_device needs eps^0 + eps^1 only)."""
    Rt = rot_x(eps * al) * rot_y(eps * be)
    pos = sp.Matrix([eps * x, eps * y, 0]) + Rt * sp.Matrix([r * sp.cos(ang), r * sp.sin(ang), d])
    vel = pos.diff(t)
    T = sp.Rational(1, 2) * m * (vel.T * vel)[0]
    return [sp.simplify(eps_part(T, k)) for k in range(orders)]


def rotor_energy_parts():
    """Exact kinetic energy of housing (mass M_k, transverse A_k), rotor (m_p, A_p, C_p, spinning
    with phi_0) and motor rotor (J - C_p about the fixed spin axis), orders eps^0..eps^2."""
    Rh = rot_x(eps * al) * rot_y(eps * be)
    Rr = Rh * rot_z(ph0)
    vel_G = sp.Matrix([eps * x, eps * y, 0]).diff(t)

    def body_omega(R):
        W = R.T * R.diff(t)        # skew matrix of the angular velocity in body axes
        return sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
    wh = body_omega(Rh)
    wr = body_omega(Rr)
    T = (sp.Rational(1, 2) * (M_k + m_p) * (vel_G.T * vel_G)[0]
         + sp.Rational(1, 2) * A_k * (wh[0]**2 + wh[1]**2)          # housing polar moment: O(eps^4)
         + sp.Rational(1, 2) * (A_p * (wr[0]**2 + wr[1]**2) + C_p * wr[2]**2)
         + sp.Rational(1, 2) * (J - C_p) * Om**2)
    # the parts unsimplified: only their sum is compared (simplified there)
    return [eps_part(T, k) for k in range(3)], wr[2]


def u_D(d):
    return x + d * be


def v_D(d):
    return y - d * al


def model_point_mass_energy(m, r, d, ang):
    """Model kinetic energy of a small mass: orders eps^0 and eps^1 (assumption (2.2))."""
    ang_d = ang.diff(t)
    return (sp.Rational(1, 2) * m * r**2 * ang_d**2
            + m * r * ang_d * (-u_D(d).diff(t) * sp.sin(ang) + v_D(d).diff(t) * sp.cos(ang)))


M_ = M_k + m_p
A_ = A_k + A_p
C_ = C_p
T_rotor_model = (sp.Rational(1, 2) * M_ * (x.diff(t)**2 + y.diff(t)**2)
                 + sp.Rational(1, 2) * A_ * (al.diff(t)**2 + be.diff(t)**2)
                 + sp.Rational(1, 2) * J * Om**2 + C_ * Om * al.diff(t) * be)


def check_energy_truncation(out):
    """Derive the model energies from the exact ones; return the dropped eps^2 terms."""
    m, r, d = sp.symbols('m r d', positive=True)
    ang = sp.Function('phi', real=True)(t)
    parts = point_mass_energy_parts(m, r, d, ang)
    kept = parts[0] + parts[1]
    assert sp.simplify(sp.expand(kept - model_point_mass_energy(m, r, d, ang))) == 0, \
        'point-mass energy: orders eps^0 + eps^1 differ from the model'
    rparts, wz = rotor_energy_parts()
    assert sp.simplify(sp.expand(rparts[0] + rparts[1] + rparts[2] - T_rotor_model)) == 0, \
        'rotor energy to order eps^2 differs from the model'
    out['spin_rate_component'] = sp.simplify(sp.trigsimp(sp.expand(wz)))   # the same, in half the time
    out['dropped_point_mass_eps2'] = sp.simplify(parts[2])
    # The dropped small-mass terms contain the paper's 1/2 m (u_D'^2 + v_D'^2):
    rest = sp.simplify(sp.expand(parts[2] - sp.Rational(1, 2) * m * (u_D(d).diff(t)**2 + v_D(d).diff(t)**2)))
    out['dropped_point_mass_eps2_beyond_paper'] = rest
    return out


# ----------------------------------------------------------------------------------------------
# 2. The model with planes as data


class Plane:
    def __init__(self, j, nballs):
        self.j = j
        self.d = sp.Symbol('d_%d' % j, real=True)
        self.m0 = sp.Symbol('m_%d0' % j, nonnegative=True)
        self.r0 = sp.Symbol('r_%d0' % j, positive=True)
        self.psi0 = sp.Symbol('psi_%d0' % j, real=True)
        self.m = [sp.Symbol('m_%d%d' % (j, i), positive=True) for i in range(1, nballs + 1)]
        self.r = [sp.Symbol('r_%d%d' % (j, i), positive=True) for i in range(1, nballs + 1)]
        self.h = [sp.Symbol('h_%d%d' % (j, i), nonnegative=True) for i in range(1, nballs + 1)]
        self.phi = [sp.Function('phi_%d%d' % (j, i), real=True)(t) for i in range(1, nballs + 1)]

    def unbalance_angle(self):
        return ph0 + self.psi0


_EQUATIONS = {}     # (T, V, R, ball coordinates) -> residuals (Model.equations)


class Model:
    """Energies, Rayleigh function and Lagrange residuals for the given planes."""

    def __init__(self, planes):
        self.planes = planes
        self.balls = [(p, i) for p in planes for i in range(len(p.m))]
        self.phis = [p.phi[i] for p, i in self.balls]
        T = T_rotor_model
        for p in planes:
            T += model_point_mass_energy(p.m0, p.r0, p.d, p.unbalance_angle())
            for i in range(len(p.m)):
                T += model_point_mass_energy(p.m[i], p.r[i], p.d, p.phi[i])
        self.T = T
        # supports: left at p = -l_L, right at p = +l_R
        xl, yl = x - l_L * be, y + l_L * al
        xr, yr = x + l_R * be, y - l_R * al
        self.V = sp.Rational(1, 2) * (c_Lx * xl**2 + c_Ly * yl**2 + c_Rx * xr**2 + c_Ry * yr**2)
        self.R_supports = sp.Rational(1, 2) * (h_Lx * xl.diff(t)**2 + h_Ly * yl.diff(t)**2
                                               + h_Rx * xr.diff(t)**2 + h_Ry * yr.diff(t)**2)
        self.R_balls = sum((sp.Rational(1, 2) * p.h[i] * p.r[i]**2 * (p.phi[i].diff(t) - Om)**2
                            for p, i in self.balls), sp.Integer(0))
        self.R = self.R_supports + self.R_balls
        # generalized force of the motor torque and the resistance torque on phi_0
        self.Q_motor = Lfun(Om) - k_r * Om

    def residual(self, q):
        """Lagrange residual d/dt dT/dq' - dT/dq + dV/dq + dR/dq' (= generalized force)."""
        qd = q.diff(t)
        return sp.expand(self.T.diff(qd).diff(t) - self.T.diff(q) + self.V.diff(q) + self.R.diff(qd))

    def equations(self):
        """Residuals: rotor q (4), balls, and phi_0 (motor: residual - Q_motor = 0)."""
        # the residuals depend on T, V, R and the ball coordinates only: a model built again with the
        # same energies (derive_device's models without gravity, the gravity model of the
        # perturbation check) gets the residuals already derived (the expansion is the costly part)
        key = (self.T, self.V, self.R, tuple(self.phis))
        if key not in _EQUATIONS:
            eq_q = [self.residual(q) for q in q_rotor]
            eq_b = [self.residual(f) for f in self.phis]
            eq_0 = self.residual(ph0)       # = torque the drive must supply (prescribed speed)
            _EQUATIONS[key] = (eq_q, eq_b, eq_0)
        eq_q, eq_b, eq_0 = _EQUATIONS[key]
        return list(eq_q), list(eq_b), eq_0

    def energy(self):
        return self.T + self.V

    def dissipation_2R(self):
        """2R: power dissipated by supports and ball resistance (k_r Omega^2 counted separately)."""
        return 2 * self.R


# ----------------------------------------------------------------------------------------------
# Symbols for the state (for printing and numerics)

Omega, dOmega = sp.symbols('Omega Omega_dot', real=True)


def state_symbols(model):
    """Map derivatives of the coordinate functions to plain symbols (highest derivative first)."""
    coords = q_rotor + [ph0] + model.phis
    names = ['x', 'y', 'alpha', 'beta', 'phi_0'] + [str(f.func) for f in model.phis]
    sub = {}
    acc, vel, pos = [], [], []
    for f, n in zip(coords, names):
        a, v, s = sp.symbols('%s_dd %s_d %s' % (n, n, n), real=True)
        sub[f.diff(t, 2)] = a
        sub[f.diff(t)] = v
        sub[f] = s
        acc.append(a)
        vel.append(v)
        pos.append(s)
    return sub, acc, vel, pos


def to_symbols(expr, sub):
    # xreplace is simultaneous and top-down: a second derivative is replaced as a whole before its
    # first derivative or its function is reached (the same result as subs() key by key, highest
    # derivative first, in a fraction of the time)
    return sp.sympify(expr).xreplace(sub)


# ----------------------------------------------------------------------------------------------
# Check (a): constant speed gives (3.2)/(3.4) [(3.5)-(3.8)]


def lumped():
    """(2.9), (2.11) written out by hand (docs/rotor.md)."""
    c = dict(c_x=c_Lx + c_Rx, c_y=c_Ly + c_Ry, c_alpha=c_Ly * l_L**2 + c_Ry * l_R**2,
             c_beta=c_Lx * l_L**2 + c_Rx * l_R**2, c_xbeta=c_Lx * l_L - c_Rx * l_R,
             c_yalpha=c_Ly * l_L - c_Ry * l_R)
    h = dict(h_x=h_Lx + h_Rx, h_y=h_Ly + h_Ry, h_alpha=h_Ly * l_L**2 + h_Ry * l_R**2,
             h_beta=h_Lx * l_L**2 + h_Rx * l_R**2, h_xbeta=h_Lx * l_L - h_Rx * l_R,
             h_yalpha=h_Ly * l_L - h_Ry * l_R)
    c.update(h)
    return c


def paper_equations(model, omega, angle=None):
    """(3.2)/(3.6) and (3.4)/(3.8) of docs/rotor.md, written by hand with the lumped coefficients.
    Default: phi_0 = omega t (omega constant).  With angle = phi_0(t) and omega = phi_0'(t): the
    same formulas with omega replaced by Omega(t) and the unbalance carried at phi_0(t) + psi_0
    (the 'naive' substitution, used to exhibit what the variable speed adds)."""
    k = lumped()
    if angle is None:
        angle = omega * t
    rot_eq = [None] * 4
    su2 = []
    sv2 = []
    for p in model.planes:
        ang0 = angle + p.psi0
        su = p.m0 * p.r0 * sp.cos(ang0) + sum(p.m[i] * p.r[i] * sp.cos(p.phi[i]) for i in range(len(p.m)))
        sv = p.m0 * p.r0 * sp.sin(ang0) + sum(p.m[i] * p.r[i] * sp.sin(p.phi[i]) for i in range(len(p.m)))
        su2.append(su.diff(t, 2))
        sv2.append(sv.diff(t, 2))
    xd, yd, ad, bd = [f.diff(t) for f in q_rotor]
    rot_eq[0] = M_ * x.diff(t, 2) + k['h_x'] * xd + k['c_x'] * x - k['h_xbeta'] * bd - k['c_xbeta'] * be + sum(su2)
    rot_eq[1] = M_ * y.diff(t, 2) + k['h_y'] * yd + k['c_y'] * y + k['h_yalpha'] * ad + k['c_yalpha'] * al + sum(sv2)
    rot_eq[2] = (A_ * al.diff(t, 2) + k['h_alpha'] * ad + k['c_alpha'] * al + C_ * omega * bd
                 + k['h_yalpha'] * yd + k['c_yalpha'] * y - sum(p.d * s for p, s in zip(model.planes, sv2)))
    rot_eq[3] = (A_ * be.diff(t, 2) + k['h_beta'] * bd + k['c_beta'] * be - C_ * omega * ad
                 - k['h_xbeta'] * xd - k['c_xbeta'] * x + sum(p.d * s for p, s in zip(model.planes, su2)))
    ball_eq = []
    for p in model.planes:
        uDdd = x.diff(t, 2) + p.d * be.diff(t, 2)
        vDdd = y.diff(t, 2) - p.d * al.diff(t, 2)
        for i in range(len(p.m)):
            ph = p.phi[i]
            ball_eq.append(p.m[i] * p.r[i] * (p.r[i] * ph.diff(t, 2) - uDdd * sp.sin(ph) + vDdd * sp.cos(ph))
                           + p.h[i] * p.r[i]**2 * (ph.diff(t) - omega))
    return rot_eq, ball_eq


def check_constant_speed(model, eq_q, eq_b):
    omega = sp.Symbol('omega', real=True)
    sub = {ph0: omega * t}
    rot_p, ball_p = paper_equations(model, omega)
    for k, (a, b) in enumerate(zip(eq_q, rot_p)):
        diff = sp.simplify(sp.expand(a.subs(sub).doit() - b.doit()))
        assert diff == 0, 'constant speed: rotor equation %d differs from (3.2): %s' % (k, diff)
    for k, (a, b) in enumerate(zip(eq_b, ball_p)):
        diff = sp.simplify(sp.expand(a.subs(sub).doit() - b.doit()))
        assert diff == 0, 'constant speed: ball equation %d differs from (3.4): %s' % (k, diff)


def check_variable_speed_extras(model, eq_q, eq_b):
    """Derived equations minus (3.2)/(3.4) with omega -> Omega(t) and the unbalance at phi_0(t):
    the only difference is C Omega' beta in the alpha equation.  Returns the differences."""
    rot_p, ball_p = paper_equations(model, Om, angle=ph0)
    extras = [sp.simplify(sp.expand(a - b.doit())) for a, b in zip(eq_q + eq_b, rot_p + ball_p)]
    expected = [0, 0, C_ * Om.diff(t) * be, 0] + [0] * len(eq_b)
    for k, (e, w) in enumerate(zip(extras, expected)):
        assert sp.simplify(e - w) == 0, 'variable-speed extra term of equation %d: %s (expected %s)' % (k, e, w)
    return extras


# ----------------------------------------------------------------------------------------------
# Check (b): rotating-frame ball equation with the Euler terms


def check_rotating_frame(out):
    """From the fixed-frame ball equation (3.4) with phi_0(t) general, show
        m r^2 (psi'' + Omega') + h r^2 psi' = m r (a_xi sin psi - a_eta cos psi),
        a_xi  = xi_D''  - 2 Omega eta_D' - Omega^2 xi_D  - Omega' eta_D,
        a_eta = eta_D'' + 2 Omega xi_D'  - Omega^2 eta_D + Omega' xi_D,
    and that (a_xi, a_eta) is the absolute acceleration of D on the rotor axes."""
    m, r, h = sp.symbols('m r h', positive=True)
    psi = sp.Function('psi', real=True)(t)
    xi = sp.Function('xi_D', real=True)(t)
    eta = sp.Function('eta_D', real=True)(t)
    c0, s0 = sp.cos(ph0), sp.sin(ph0)
    uD = xi * c0 - eta * s0                 # (3.12) with phi_0(t) in place of omega t
    vD = xi * s0 + eta * c0
    phi = ph0 + psi
    fixed = (m * r * (r * phi.diff(t, 2) - uD.diff(t, 2) * sp.sin(phi) + vD.diff(t, 2) * sp.cos(phi))
             + h * r**2 * (phi.diff(t) - Om))
    W, dW = Om, Om.diff(t)
    a_xi = xi.diff(t, 2) - 2 * W * eta.diff(t) - W**2 * xi - dW * eta
    a_eta = eta.diff(t, 2) + 2 * W * xi.diff(t) - W**2 * eta + dW * xi
    rotating = m * r**2 * (psi.diff(t, 2) + dW) + h * r**2 * psi.diff(t) - m * r * (a_xi * sp.sin(psi) - a_eta * sp.cos(psi))
    d1 = sp.simplify(sp.expand(sp.expand_trig(fixed - rotating)))
    assert d1 == 0, 'rotating frame: ball equation differs: %s' % d1
    d2 = sp.simplify(sp.expand(uD.diff(t, 2) * c0 + vD.diff(t, 2) * s0 - a_xi))
    d3 = sp.simplify(sp.expand(-uD.diff(t, 2) * s0 + vD.diff(t, 2) * c0 - a_eta))
    assert d2 == 0 and d3 == 0, 'rotating frame: projected acceleration of D differs: %s, %s' % (d2, d3)
    out['rotating_ball_equation'] = sp.Eq(m * r**2 * (psi.diff(t, 2) + dW) + h * r**2 * psi.diff(t),
                                          m * r * (a_xi * sp.sin(psi) - a_eta * sp.cos(psi)))
    out['a_xi'] = a_xi
    out['a_eta'] = a_eta
    return out


# ----------------------------------------------------------------------------------------------
# Check (c): energy balance, identically along the equations


def check_energy_identity(model, eq_q, eq_b, eq_0):
    """dE/dt - (P_drive - D) == sum_q q' * residual_q (Lagrange identity for T quadratic in the
    velocities).  Motor: P_drive - D = L Omega - k_r Omega^2 - 2R, residual_0 = eq_0 - L + k_r Omega.
    Prescribed speed: P_drive = Omega * eq_0 (the drive torque), D = 2R."""
    E = model.energy()
    dEdt = E.diff(t)
    coords = q_rotor + model.phis
    combo = sum((c.diff(t) * e for c, e in zip(coords, eq_q + eq_b)), sp.Integer(0))
    # motor
    res0 = eq_0 - model.Q_motor
    lhs = dEdt - (Lfun(Om) * Om - k_r * Om**2 - model.dissipation_2R()) - combo - Om * res0
    d = sp.simplify(sp.expand(lhs))
    assert d == 0, 'energy identity (motor) fails: %s' % d
    # prescribed speed: the drive supplies the torque eq_0, so dE/dt = Omega eq_0 - 2R on solutions
    lhs = dEdt - (Om * eq_0 - model.dissipation_2R()) - combo
    d = sp.simplify(sp.expand(lhs))
    assert d == 0, 'energy identity (prescribed speed) fails: %s' % d


# ----------------------------------------------------------------------------------------------
# Numeric check values


def default_params(two_planes):
    """docs/rotor.md default example; second plane and plane-1 damping as data/rotor_two_planes.ini."""
    P = {M_k: 6, A_k: sp.Rational(12, 100), m_p: 4, A_p: sp.Rational(4, 100), C_p: sp.Rational(3, 100),
         l_L: sp.Rational(20, 100), l_R: sp.Rational(15, 100),
         c_Lx: 100000, c_Ly: 100000, c_Rx: 150000, c_Ry: 150000,
         h_Lx: 100, h_Ly: 100, h_Rx: 150, h_Ry: 150}
    planes = [dict(d=sp.Rational(10, 100), m0=sp.Rational(2, 100), r0=sp.Rational(1, 10), psi0=0,
                   m=[sp.Rational(5, 100)] * 2, r=[sp.Rational(1, 10)] * 2,
                   h=[sp.Rational(1, 10)] * 2 if not two_planes else [sp.Rational(1, 2)] * 2,
                   psi=[sp.Float('1.0'), sp.Float('2.5')], rate=[sp.Float('0.5'), sp.Float('-1.0')])]
    if two_planes:
        planes.append(dict(d=sp.Rational(-12, 100), m0=sp.Rational(15, 1000), r0=sp.Rational(9, 100),
                           psi0=sp.Float('2.0'), m=[sp.Rational(4, 100)] * 2, r=[sp.Rational(9, 100)] * 2,
                           h=[sp.Rational(1, 2)] * 2, psi=[sp.Float('-0.5'), sp.Float('2.0')],
                           rate=[sp.Float('0.25'), sp.Float('0.75')]))
    return P, planes


# Fixed check state (SI): rotor coordinates, rates, rotor angle; speeds; motor.
STATE = dict(x=1.0e-4, y=-2.0e-4, alpha=3.0e-4, beta=-1.0e-4,
             x_d=0.01, y_d=-0.02, alpha_d=0.05, beta_d=0.03, phi_0=0.3)
PRESCRIBED = dict(Omega=300.0, Omega_dot=50.0)
MOTOR = dict(L_0=5.0, Omega_0=600.0, k_r=1.0e-3, J_motor_rotor=0.01, Omega=300.0)


def numeric_case(model, eq_q, eq_b, eq_0, two_planes):
    prec = 30
    P, pdata = default_params(two_planes)
    sub, acc, vel, pos = state_symbols(model)
    par = dict(P)
    for p, pd in zip(model.planes, pdata):
        par.update({p.d: pd['d'], p.m0: pd['m0'], p.r0: pd['r0'], p.psi0: pd['psi0']})
        for i in range(len(p.m)):
            par.update({p.m[i]: pd['m'][i], p.r[i]: pd['r'][i], p.h[i]: pd['h'][i]})
    names = ['x', 'y', 'alpha', 'beta']
    base = {}
    for k, n in enumerate(names):
        base[pos[k]] = sp.Float(STATE[n], prec)
        base[vel[k]] = sp.Float(STATE[n + '_d'], prec)
    base[pos[4]] = sp.Float(STATE['phi_0'], prec)
    ball_state = []
    for p, pd in zip(model.planes, pdata):
        for i in range(len(p.m)):
            ball_state.append((pd['psi'][i], pd['rate'][i]))

    def state_at(W):
        s = dict(base)
        s[vel[4]] = sp.Float(W, prec)
        for k, (ps, rt) in enumerate(ball_state):
            s[pos[5 + k]] = sp.Float(STATE['phi_0'], prec) + ps      # phi = phi_0 + psi
            s[vel[5 + k]] = sp.Float(W, prec) + rt                   # phi' = Omega + psi'
        return s

    eqs_q = [to_symbols(e, sub) for e in eq_q]
    eqs_b = [to_symbols(e, sub) for e in eq_b]
    e0 = to_symbols(eq_0, sub)
    E = to_symbols(model.energy(), sub)
    dEdt = sum((E.diff(s) * v for s, v in zip(pos, vel)), sp.Integer(0)) + \
        sum((E.diff(v) * a for v, a in zip(vel, acc)), sp.Integer(0))
    twoR = to_symbols(model.dissipation_2R(), sub)
    result = {'parameters': {str(k): float(v) for k, v in P.items()},
              'planes': [{k: ([float(u) for u in v] if isinstance(v, list) else float(v))
                          for k, v in pd.items()} for pd in pdata],
              'state': dict(STATE)}

    # (a) prescribed speed
    W, dW = PRESCRIBED['Omega'], PRESCRIBED['Omega_dot']
    s = state_at(W)
    s[acc[4]] = sp.Float(dW, prec)
    s.update({k: sp.Float(v, prec) for k, v in par.items()})
    s[J] = par[C_p]     # prescribed speed: the spin energy counted is the rotor's own (J = C_p)
    unknown = acc[:4] + acc[5:]
    Amat, bvec = sp.linear_eq_to_matrix([e.xreplace(s) for e in eqs_q + eqs_b], unknown)
    sol = Amat.evalf(prec).LUsolve(bvec.evalf(prec))
    sol_map = dict(zip(unknown, sol))
    s_all = dict(s)
    s_all.update(sol_map)
    torque = e0.xreplace(s_all).evalf(prec)
    P_drive = sp.Float(W, prec) * torque
    D = twoR.xreplace(s_all).evalf(prec)
    dE = dEdt.xreplace(s_all).evalf(prec)
    bal = dE - (P_drive - D)
    assert abs(bal) <= 1e-12 * max(abs(P_drive), abs(D), 1e-300), 'energy balance (prescribed): %s' % bal
    acc_names = ['x_dd', 'y_dd', 'alpha_dd', 'beta_dd'] + [str(f.func) + '_dd' for f in model.phis]
    result['prescribed'] = {'Omega': W, 'Omega_dot': dW,
                            'accelerations': {n: float(v) for n, v in zip(acc_names, sol)},
                            'drive_torque': float(torque),
                            'energy': float(E.xreplace(s_all).evalf(prec)),
                            'dE_dt': float(dE), 'drive_power': float(P_drive), 'dissipation': float(D),
                            'note': 'energy with J = C_p (the prescribed drive carries the rotor only); '
                                    'drive_torque is the phi_0 residual, the torque the drive must supply'}

    # (b) motor
    W = MOTOR['Omega']
    L0, W0, kr = MOTOR['L_0'], MOTOR['Omega_0'], MOTOR['k_r']
    Jv = par[C_p] + sp.Float(MOTOR['J_motor_rotor'], prec)
    s = state_at(W)
    s.update({k: sp.Float(v, prec) for k, v in par.items()})
    s[J] = Jv
    s[k_r] = sp.Float(kr, prec)
    Lval = sp.Float(L0, prec) * (1 - sp.Float(W, prec) / sp.Float(W0, prec))
    eq0_motor = e0 - (Lval - k_r * vel[4])
    unknown = acc
    Amat, bvec = sp.linear_eq_to_matrix([e.xreplace(s) for e in eqs_q + [eq0_motor] + eqs_b], unknown)
    # order of the equations: q (4), phi_0, balls - matches the unknowns' order
    sol = Amat.evalf(prec).LUsolve(bvec.evalf(prec))
    s_all = dict(s)
    s_all.update(dict(zip(unknown, sol)))
    P_motor = Lval * sp.Float(W, prec)
    D = (twoR.xreplace(s_all) + k_r.xreplace(s_all) * sp.Float(W, prec)**2).evalf(prec)
    dE = dEdt.xreplace(s_all).evalf(prec)
    bal = dE - (P_motor - D)
    assert abs(bal) <= 1e-12 * max(abs(P_motor), abs(D), 1e-300), 'energy balance (motor): %s' % bal
    acc_names_m = ['x_dd', 'y_dd', 'alpha_dd', 'beta_dd', 'phi_0_dd'] + [str(f.func) + '_dd' for f in model.phis]
    result['motor'] = dict(MOTOR)
    result['motor'].update({'J': float(Jv), 'L': float(Lval),
                            'accelerations': {n: float(v) for n, v in zip(acc_names_m, sol)},
                            'energy': float(E.xreplace(s_all).evalf(prec)),
                            'dE_dt': float(dE), 'motor_power': float(P_motor), 'dissipation': float(D),
                            'note': 'L(Omega) = L_0 (1 - Omega/Omega_0); dissipation includes k_r Omega^2'})
    return result


# ----------------------------------------------------------------------------------------------
# Printing


def pretty_equations(model, eq_q, eq_b, eq_0, latex):
    sub, acc, vel, pos = state_symbols(model)
    extra = {acc[4]: dOmega, vel[4]: Omega}
    names = ['x', 'y', 'alpha', 'beta', 'balls...', 'phi_0 (motor)']
    lines = []

    def show(title, expr):
        e = sp.collect(sp.expand(to_symbols(expr, sub).subs(extra)), acc + [dOmega, Omega])
        lines.append(title)
        lines.append(sp.latex(e) + ' = 0' if latex else sp.pretty(sp.Eq(e, 0), use_unicode=False, wrap_line=False))
        lines.append('')
    for n, e in zip(names[:4], eq_q):
        show('[%s equation]' % n, e)
    for f, e in zip(model.phis, eq_b):
        show('[%s equation]' % f.func, e)
    show('[phi_0 equation, motor drive]', eq_0 - model.Q_motor)
    return '\n'.join(lines)


def compare_json(a, b, path=''):
    """Compare two JSON values; numbers to relative 1e-12. Returns a list of differences."""
    diffs = []
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            diffs.append('%s: keys %s vs %s' % (path, sorted(a), sorted(b)))
        for k in set(a) & set(b):
            diffs += compare_json(a[k], b[k], path + '/' + k)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            diffs.append('%s: lengths %d vs %d' % (path, len(a), len(b)))
        for k, (u, v) in enumerate(zip(a, b)):
            diffs += compare_json(u, v, '%s[%d]' % (path, k))
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if not (abs(a - b) <= 1e-12 * max(abs(a), abs(b)) or a == b):
            diffs.append('%s: %r vs %r' % (path, a, b))
    elif a != b:
        diffs.append('%s: %r vs %r' % (path, a, b))
    return diffs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--latex', action='store_true')
    ap.add_argument('--quiet', action='store_true')
    ap.add_argument('--write-json')
    ap.add_argument('--check-json')
    args = ap.parse_args()

    info = check_energy_truncation({})
    print('check: model kinetic energy = exact energy truncated (rotor to eps^2, small masses to eps^1): OK')
    print('spin component of the rotor angular velocity (body axes): %s' % info['spin_rate_component'])
    print('dropped eps^2 terms of a small point mass m at radius r, angle phi, plane z = d:')
    print('  ' + str(info['dropped_point_mass_eps2']))
    print('  of which beyond the paper\'s 1/2 m (u_D\'^2 + v_D\'^2):')
    print('  ' + str(info['dropped_point_mass_eps2_beyond_paper']))

    info = check_rotating_frame(info)
    print('check: rotating-frame ball equation with Euler terms follows from (3.4) for general phi_0(t): OK')
    results = {}
    for name, nballs in (('one_plane', [2]), ('two_planes', [2, 2])):
        planes = [Plane(j + 1, n) for j, n in enumerate(nballs)]
        model = Model(planes)
        eq_q, eq_b, eq_0 = model.equations()
        check_constant_speed(model, eq_q, eq_b)
        print('check (%s): Omega constant gives (3.2)/(3.4) [(3.5)-(3.8)] exactly: OK' % name)
        extras = check_variable_speed_extras(model, eq_q, eq_b)
        print('check (%s): variable speed = (3.2)/(3.4) with omega -> Omega(t), unbalance at phi_0(t), '
              'plus only %s in the alpha equation: OK' % (name, extras[2]))
        check_energy_identity(model, eq_q, eq_b, eq_0)
        print('check (%s): dE/dt - (P - D) = sum of q\' times the equation residuals (motor and prescribed): OK'
              % name)
        results[name] = numeric_case(model, eq_q, eq_b, eq_0, name == 'two_planes')
        for case in ('prescribed', 'motor'):
            r = results[name][case]
            P = r.get('drive_power', r.get('motor_power'))
            print('check (%s, %s): dE/dt = %.15g, P - D = %.15g (relative difference below 1e-12): OK'
                  % (name, case, r['dE_dt'], P - r['dissipation']))
        if not args.quiet and name == 'one_plane':
            print('\nEquations of motion, one plane, two balls (fixed frame, variable spin):\n')
            print(pretty_equations(model, eq_q, eq_b, eq_0, args.latex))
            print('rotating-frame ball equation:')
            print(sp.pretty(info['rotating_ball_equation'], use_unicode=False, wrap_line=False))
            print()
    # device physics (docs/device.md sections 2-4): gravity, normal force, resistance, stiction,
    # rolling inertia, contact; new keys of the JSON, the keys above are unchanged
    import derive_device
    results.update(derive_device.run(sys.modules[__name__]))
    results['generator'] = 'tools/derive/derive_rotor.py (sympy %s)' % sp.__version__
    if args.write_json:
        with open(args.write_json, 'w') as f:
            json.dump(results, f, indent=1, sort_keys=True)
            f.write('\n')
        print('wrote %s' % args.write_json)
    if args.check_json:
        with open(args.check_json) as f:
            ref = json.load(f)
        ref.pop('generator', None)
        now = json.loads(json.dumps(results))
        now.pop('generator', None)
        diffs = compare_json(now, ref)
        if diffs:
            print('check_values differ from %s:' % args.check_json)
            for d in diffs[:20]:
                print('  ' + d)
            return 1
        print('check: %s equals the values computed now (relative 1e-12): OK' % args.check_json)
    return 0


if __name__ == '__main__':
    sys.exit(main())
