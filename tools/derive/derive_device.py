"""Device physics of the ball balancer (docs/device.md sections 2-4), derived with SymPy.

Imported by derive_rotor.py (run(dr) with dr the derive_rotor module); it reuses that module's
energies, planes, Lagrange residuals and numeric conventions and adds:

 1. gravity: the in-plane component g_s = g sin(theta) along -y of the fixed axes; potential of the
    rotor-housing (centre of mass at the reference point) and of every small mass, expanded from the
    exact height like the kinetic energy (small masses to order eps^1); the equations' new terms;
    the static offset of the linear part (closed form); the first-order periodic (1X) response of the
    balanced state (3.14) to gravity (harmonic balance of the linearized equations);
 2. the normal force N of a ball on its track, derived as the constraint force of the radial
    coordinate (the ball at a variable radius R(t), residual at R = r), fixed and rotating frame;
 3. rolling resistance f N against the relative motion; stiction: a stuck ball (psi' = psi'' = 0)
    as a mass fixed to the rotor (Lagrange's equations of the constrained system) and the holding
    force H it needs, to compare with mu N;
 4. rolling inertia of a solid ball of radius rho rolling without sliding on the outer race (contact
    at radius r + rho): derived from the rolling condition, its kinetic energy and its terms;
 5. contact of two balls on a shared track: the angle gap, the generalized impact law with the
    model's mass matrix (restitution e), the energy loss in closed form, the pair-only limit, and the
    resting contact (two balls as one body) with its contact force.
Every check raises AssertionError when it fails; the printed lines end in ': OK'.
"""
import sympy as sp

G_STD = 9.80665             # m/s^2
THETA = 1.2                 # rad, shaft angle of the check values (sin and cos both non-trivial)
RHO = 0.0115                # m, ball radius of the check values (solid steel ball of 50 g: 11.5 mm)
F_ROLL = 0.02               # rolling-resistance coefficient of the check values
E_REST = 0.5                # coefficient of restitution of the check values
PREC = 30

g_s = sp.Symbol('g_s', real=True)          # g sin(theta), m/s^2


def _say(msg):
    print(msg)


# ----------------------------------------------------------------------------------------------
# Model with the device terms


def small_masses(p):
    """(mass, radius, angle) of the unbalance (i = 0) and the balls of plane p."""
    return [(p.m0, p.r0, p.unbalance_angle())] + [(p.m[i], p.r[i], p.phi[i]) for i in range(len(p.m))]


def cached_equations(mdl):
    """Model.equations() once per model (the residuals are expanded: the costly part)."""
    if getattr(mdl, '_eqs', None) is None:
        mdl._eqs = type(mdl).equations(mdl)
    return mdl._eqs


def make_model(dr, planes, gravity=False, rho=None, stuck=()):
    """A derive_rotor Model with gravity (potential g_s * height), rolling inertia (rho: dict
    ball -> radius symbol) and stuck balls (list of (plane, i, psi symbol): phi = phi_0 + psi)."""
    mdl = dr.Model(planes)
    if gravity:
        V = dr.M_ * dr.y
        for p in planes:
            for m, r, ang in small_masses(p):
                V += m * (dr.v_D(p.d) + r * sp.sin(ang))
        mdl.V = mdl.V + g_s * V
    if rho:
        for (p, i), rh in rho.items():
            mdl.T = mdl.T + rolling_energy(dr, p.m[i], p.r[i], rh, p.phi[i])
    for p, i, c in stuck:
        f = p.phi[i]
        sub = [(f.diff(dr.t, 2), dr.Om.diff(dr.t)), (f.diff(dr.t), dr.Om), (f, dr.ph0 + c)]
        for attr in ('T', 'V', 'R', 'R_balls'):
            e = getattr(mdl, attr)
            for a, b in sub:
                e = e.subs(a, b)
            setattr(mdl, attr, e)
        mdl.phis = [g for g in mdl.phis if g != f]
        mdl.balls = [(pp, ii) for pp, ii in mdl.balls if not (pp is p and ii == i)]
    mdl.equations = lambda: cached_equations(mdl)
    return mdl


def rolling_energy(dr, m, r, rho, phi):
    """Rotational kinetic energy of a solid ball (radius rho) whose centre runs on radius r and which
    rolls without sliding on the outer race (contact at radius r + rho), derived from the rolling
    condition in the rotor's axes (planar; the housing tilt is a small-mass eps^2 term, dropped)."""
    w = sp.Symbol('w_rel', real=True)                    # spin of the ball relative to the rotor
    psid = phi.diff(dr.t) - dr.Om
    # contact point velocity relative to the race: centre r psi' e_t + (w e_z) x (rho e_r) = (r psi' + w rho) e_t
    w_sol = sp.solve(sp.Eq(r * psid + w * rho, 0), w)[0]
    I_ball = sp.Rational(2, 5) * m * rho**2
    return sp.Rational(1, 2) * I_ball * (dr.Om + w_sol)**2


# ----------------------------------------------------------------------------------------------
# Numerics (30 digits, like derive_rotor.numeric_case)


def F(v):
    return sp.Float(v, PREC)


def params_for(dr, model, two_planes):
    P, pdata = dr.default_params(two_planes)
    par = dict(P)
    for p, pd in zip(model.planes, pdata):
        par.update({p.d: pd['d'], p.m0: pd['m0'], p.r0: pd['r0'], p.psi0: pd['psi0']})
        for i in range(len(p.m)):
            par.update({p.m[i]: pd['m'][i], p.r[i]: pd['r'][i], p.h[i]: pd['h'][i]})
    return par, pdata


class Case:
    """Numeric evaluation of a model at the check state of derive_rotor (rotor state STATE, balls at
    phi_0 + psi with relative rates 'rate'), optionally with changed ball angles/rates."""

    def __init__(self, dr, model, two_planes, motor, extra=None, psi=None, rate=None):
        self.dr, self.model, self.motor = dr, model, motor
        self.sub, self.acc, self.vel, self.pos = dr.state_symbols(model)
        par, pdata = params_for(dr, model, two_planes)
        W = dr.MOTOR['Omega'] if motor else dr.PRESCRIBED['Omega']
        s = {}
        for k, n in enumerate(['x', 'y', 'alpha', 'beta']):
            s[self.pos[k]] = F(dr.STATE[n])
            s[self.vel[k]] = F(dr.STATE[n + '_d'])
        ph0v = F(dr.STATE['phi_0'])
        s[self.pos[4]] = ph0v
        s[self.vel[4]] = F(W)
        self.ballstate = {}
        for p, pd in zip(model.planes, pdata):
            for i in range(len(p.m)):
                ps = (psi or {}).get((p.j, i), pd['psi'][i])
                rt = (rate or {}).get((p.j, i), pd['rate'][i])
                self.ballstate[(p.j, i)] = (F(ps), F(rt))
        for f in model.phis:
            j, i = int(str(f.func)[4]), int(str(f.func)[5]) - 1
            ps, rt = self.ballstate[(j, i)]
            k = 5 + model.phis.index(f)
            s[self.pos[k]] = ph0v + ps
            s[self.vel[k]] = F(W) + rt
        s.update({k: F(v) for k, v in par.items()})
        if motor:
            s[dr.J] = par[dr.C_p] + F(dr.MOTOR['J_motor_rotor'])
            s[dr.k_r] = F(dr.MOTOR['k_r'])
            self.L = F(dr.MOTOR['L_0']) * (1 - F(W) / F(dr.MOTOR['Omega_0']))
        else:
            s[dr.J] = par[dr.C_p]
            s[self.acc[4]] = F(dr.PRESCRIBED['Omega_dot'])
        s.update(extra or {})
        self.s = s
        self.W = W

    def sym(self, expr):
        # xreplace is simultaneous and top-down: a derivative node is replaced as a whole before its
        # function is reached, which is what derive_rotor.to_symbols does by ordering the keys
        return sp.sympify(expr).xreplace(self.sub)

    def solve(self, eq_q, eq_b, eq_0, extra_b=None):
        """Solve for the accelerations; extra_b: list of expressions added to the ball residuals
        (generalized resistance forces, may contain accelerations).  Returns dict name -> value."""
        dr = self.dr
        eqs = [self.sym(e) for e in eq_q]
        if self.motor:
            eqs.append(self.sym(eq_0) - (self.L - dr.k_r * self.vel[4]))
        eb = [self.sym(e) for e in eq_b]
        if extra_b:
            eb = [a + self.sym(b) for a, b in zip(eb, extra_b)]
        eqs += eb
        unknown = self.acc[:4] + ([self.acc[4]] if self.motor else []) + self.acc[5:]
        A, b = sp.linear_eq_to_matrix([e.xreplace(self.s) for e in eqs], unknown)
        sol = A.evalf(PREC).LUsolve(b.evalf(PREC))
        self.s_all = dict(self.s)
        self.s_all.update(dict(zip(unknown, sol)))
        self.unknown = unknown
        return {str(u).replace('_dd', '') + '_dd': v for u, v in zip(unknown, sol)}

    def value(self, expr):
        return self.sym(expr).xreplace(self.s_all).evalf(PREC)

    def energy_balance(self, eq_0, extra_power=0):
        """E, dE/dt, drive power, dissipation at the solved state (extra_power: power of the
        resistance forces beyond 2R, negative)."""
        dr = self.dr
        E = self.sym(self.model.energy())
        dEdt = sum((E.diff(s) * v for s, v in zip(self.pos, self.vel)), sp.Integer(0)) + \
            sum((E.diff(v) * a for v, a in zip(self.vel, self.acc)), sp.Integer(0))
        twoR = self.sym(self.model.dissipation_2R()).xreplace(self.s_all).evalf(PREC)
        dE = dEdt.xreplace(self.s_all).evalf(PREC)
        if self.motor:
            P = self.L * F(self.W)
            D = twoR + F(dr.MOTOR['k_r']) * F(self.W)**2 - extra_power
            torque = None
        else:
            torque = self.value(eq_0)
            P = F(self.W) * torque
            D = twoR - extra_power
        bal = dE - (P - D)
        assert abs(bal) <= 1e-12 * max(abs(P), abs(D), 1e-300), 'energy balance: %s' % bal
        return dict(energy=E.xreplace(self.s_all).evalf(PREC), dE_dt=dE, power=P, dissipation=D, torque=torque)


def fl(d):
    if isinstance(d, dict):
        return {k: fl(v) for k, v in d.items()}
    if isinstance(d, (list, tuple)):
        return [fl(v) for v in d]
    if isinstance(d, (sp.Basic, int)) and not isinstance(d, bool):
        return float(d)
    return d


# ----------------------------------------------------------------------------------------------
# 1. Gravity


def derive_gravity_potential(dr):
    """Height of a small mass from the exact position (same rotation as the kinetic energy)."""
    m, r, d = sp.symbols('m r d', positive=True)
    ang = sp.Function('phi', real=True)(dr.t)
    eps = dr.eps
    Rt = dr.rot_x(eps * dr.al) * dr.rot_y(eps * dr.be)
    pos = sp.Matrix([eps * dr.x, eps * dr.y, 0]) + Rt * sp.Matrix([r * sp.cos(ang), r * sp.sin(ang), d])
    Y = pos[1]
    y0 = sp.simplify(dr.eps_part(Y, 0))
    y1 = sp.simplify(dr.eps_part(Y, 1))
    y2 = sp.simplify(dr.eps_part(Y, 2))
    assert sp.simplify(y0 + y1 - (dr.v_D(d) + r * sp.sin(ang))) == 0, 'height of a small mass'
    _say('check: height of a small mass to order eps^1 = v_D + r sin(phi) (dropped eps^2: %s): OK' % y2)
    # the axial coordinate (the axial weight g cos(theta) acts on it; not in the model: say what is dropped)
    z1 = sp.simplify(dr.eps_part(pos[2], 1))
    return z1


def check_gravity_terms(dr, model0, modelg):
    """The equations with gravity minus those without: exactly the hand-written terms."""
    eq0 = model0.equations()
    eqg = modelg.equations()
    Wtot = dr.M_ + sum((m for p in model0.planes for m, _, _ in small_masses(p)), sp.Integer(0))
    Dm = sum((p.d * m for p in model0.planes for m, _, _ in small_masses(p)), sp.Integer(0))
    want_q = [0, g_s * Wtot, -g_s * Dm, 0]
    want_b = [g_s * p.m[i] * p.r[i] * sp.cos(p.phi[i]) for p, i in model0.balls]
    want_0 = g_s * sum((p.m0 * p.r0 * sp.cos(p.unbalance_angle()) for p in model0.planes), sp.Integer(0))
    for a, b, w in zip(eqg[0] + eqg[1] + [eqg[2]], eq0[0] + eq0[1] + [eq0[2]], want_q + want_b + [want_0]):
        d = sp.simplify(sp.expand(a - b - w))
        assert d == 0, 'gravity term: %s' % d
    # theta = 0: the old equations
    for a, b in zip(eqg[0] + eqg[1] + [eqg[2]], eq0[0] + eq0[1] + [eq0[2]]):
        assert sp.simplify(a.subs(g_s, 0) - b) == 0
    return eqg, Wtot, Dm


def static_offset(dr, model, Wtot, Dm):
    """Equilibrium of the linear part under the weights: K q = -g_s w, solved symbolically and
    compared with the closed form y_s = -g_s (W c_alpha + c_yalpha D)/det, alpha_s = g_s (c_y D +
    c_yalpha W)/det, det = c_y c_alpha - c_yalpha^2, x_s = beta_s = 0."""
    q = sp.symbols('x_s y_s alpha_s beta_s', real=True)
    Vq = model.V.subs({dr.x: q[0], dr.y: q[1], dr.al: q[2], dr.be: q[3]})
    grads = [Vq.diff(v) for v in q]
    # the ball/unbalance weights do not depend on their angles in the rotor equations
    sol = sp.solve(grads, q, dict=True)[0]
    k = dr.lumped()
    det = k['c_y'] * k['c_alpha'] - k['c_yalpha']**2
    want = {q[0]: 0, q[1]: -g_s * (Wtot * k['c_alpha'] + k['c_yalpha'] * Dm) / det,
            q[2]: g_s * (k['c_y'] * Dm + k['c_yalpha'] * Wtot) / det, q[3]: 0}
    for v in q:
        assert sp.simplify(sol[v] - want[v]) == 0, 'static offset %s: %s vs %s' % (v, sol[v], want[v])
    return [want[v] for v in q]


def gravity_numbers(dr, modelg, eqg, offset, two_planes, gval):
    out = {}
    for motor in (False, True):
        c = Case(dr, modelg, two_planes, motor, extra={g_s: gval})
        acc = c.solve(*eqg)
        eb = c.energy_balance(eqg[2])
        blk = {'accelerations': acc, 'energy': eb['energy'], 'dE_dt': eb['dE_dt'], 'dissipation': eb['dissipation']}
        if motor:
            blk['motor_power'] = eb['power']
        else:
            blk['drive_torque'] = eb['torque']
            blk['drive_power'] = eb['power']
        out['motor' if motor else 'prescribed'] = blk
        # normal force at the same solved state (fixed- and rotating-frame formulas agree)
        out[('motor' if motor else 'prescribed') + '_N'] = normal_forces(dr, c)
    par, _ = params_for(dr, modelg, two_planes)
    par[g_s] = gval
    out['static_offset'] = {n: sp.sympify(v).subs(par).evalf(PREC) for n, v in zip(['x', 'y', 'alpha', 'beta'], offset)}
    return out


# ----------------------------------------------------------------------------------------------
# 2. Normal force


def N_fixed(dr, p, i):
    """N = m (r phi'^2 - u_D'' cos phi - (v_D'' + g_s) sin phi)."""
    ph = p.phi[i]
    t = dr.t
    return p.m[i] * (p.r[i] * ph.diff(t)**2 - dr.u_D(p.d).diff(t, 2) * sp.cos(ph)
                     - (dr.v_D(p.d).diff(t, 2) + g_s) * sp.sin(ph))


def derive_normal_force(dr):
    """N as the constraint force of a radial coordinate R(t): residual_R at R = r equals -N."""
    t = dr.t
    m, r, d, h = sp.symbols('m r d h', positive=True)
    R = sp.Function('R', real=True)(t)
    ph = sp.Function('phi', real=True)(t)
    parts = dr.point_mass_energy_parts(m, R, d, ph, orders=2)   # eps^2 is not used here
    T = parts[0] + parts[1]
    V = m * g_s * (dr.v_D(d) + R * sp.sin(ph))

    def res(qq):
        return T.diff(qq.diff(t)).diff(t) - T.diff(qq) + V.diff(qq)
    fix = [(R.diff(t, 2), 0), (R.diff(t), 0), (R, r)]
    resR = res(R)
    resP = res(ph)
    for a, b in fix:
        resR = resR.subs(a, b)
        resP = resP.subs(a, b)

    class _P:
        pass
    pp = _P()
    pp.m, pp.r, pp.phi, pp.d = [m], [r], [ph], d
    Nh = N_fixed(dr, pp, 0)
    assert sp.simplify(sp.expand(-resR - Nh)) == 0, 'normal force: %s' % sp.simplify(-resR - Nh)
    # the tangential residual at R = r is the model's ball equation (with gravity)
    ball = m * r * (r * ph.diff(t, 2) - dr.u_D(d).diff(t, 2) * sp.sin(ph) + (dr.v_D(d).diff(t, 2) + g_s) * sp.cos(ph))
    assert sp.simplify(sp.expand(resP - ball)) == 0, 'tangential residual with a radial coordinate'
    _say('check: N = -(residual of the radial coordinate at R = r) = m (r phi\'^2 - u_D\'\' cos phi '
         '- (v_D\'\' + g_s) sin phi), tangential residual = ball equation with gravity: OK')
    # rotating frame: psi, xi_D, eta_D as in derive_rotor.check_rotating_frame
    psi = sp.Function('psi', real=True)(t)
    xi = sp.Function('xi_D', real=True)(t)
    eta = sp.Function('eta_D', real=True)(t)
    c0, s0 = sp.cos(dr.ph0), sp.sin(dr.ph0)
    uD = xi * c0 - eta * s0
    vD = xi * s0 + eta * c0
    phi = dr.ph0 + psi
    W, dW = dr.Om, dr.Om.diff(t)
    a_xi = xi.diff(t, 2) - 2 * W * eta.diff(t) - W**2 * xi - dW * eta
    a_eta = eta.diff(t, 2) + 2 * W * xi.diff(t) - W**2 * eta + dW * xi
    g_xi, g_eta = -g_s * s0, -g_s * c0          # gravity (0, -g_s) on the rotor axes
    N_fix = m * (r * phi.diff(t)**2 - uD.diff(t, 2) * sp.cos(phi) - (vD.diff(t, 2) + g_s) * sp.sin(phi))
    N_rot = m * (r * (W + psi.diff(t))**2 - (a_xi - g_xi) * sp.cos(psi) - (a_eta - g_eta) * sp.sin(psi))
    dd = sp.simplify(sp.expand(sp.expand_trig(N_fix - N_rot)))
    assert dd == 0, 'normal force, rotating frame: %s' % dd
    ball_fix = m * r * (r * phi.diff(t, 2) - uD.diff(t, 2) * sp.sin(phi) + (vD.diff(t, 2) + g_s) * sp.cos(phi)) \
        + h * r**2 * psi.diff(t)
    ball_rot = m * r**2 * (psi.diff(t, 2) + dW) + h * r**2 * psi.diff(t) \
        - m * r * ((a_xi - g_xi) * sp.sin(psi) - (a_eta - g_eta) * sp.cos(psi))
    dd = sp.simplify(sp.expand(sp.expand_trig(ball_fix - ball_rot)))
    assert dd == 0, 'ball equation with gravity, rotating frame: %s' % dd
    _say('check: rotating frame: N = m (r (Omega + psi\')^2 - (a_xi - g_xi) cos psi - (a_eta - g_eta) sin psi), '
         'ball equation with a_D - g in place of a_D, (g_xi, g_eta) = -g_s (sin phi_0, cos phi_0): OK')


def normal_forces(dr, c):
    """N of every free ball at the solved state of Case c, by the fixed-frame formula, checked
    against the rotating-frame formula (a_xi, a_eta from u_D'', v_D'')."""
    out = {}
    ph0v = c.s[c.pos[4]]
    W = c.s[c.vel[4]]
    for p, i in c.model.balls:
        Nf = c.value(N_fixed(dr, p, i))
        ph = c.value(p.phi[i])
        psi = ph - ph0v
        psid = c.value(p.phi[i].diff(dr.t)) - W
        uDdd = c.value(dr.u_D(p.d).diff(dr.t, 2))
        vDdd = c.value(dr.v_D(p.d).diff(dr.t, 2))
        gv = c.s.get(g_s, 0)
        axi = uDdd * sp.cos(ph0v) + vDdd * sp.sin(ph0v)
        aeta = -uDdd * sp.sin(ph0v) + vDdd * sp.cos(ph0v)
        Nr = c.s[p.m[i]] * (c.s[p.r[i]] * (W + psid)**2 - (axi + gv * sp.sin(ph0v)) * sp.cos(psi)
                            - (aeta + gv * sp.cos(ph0v)) * sp.sin(psi))
        assert abs(Nf - Nr) <= 1e-20 * abs(Nf), 'N fixed vs rotating'
        out[str(p.phi[i].func)] = Nf
    return out


# ----------------------------------------------------------------------------------------------
# 1b. First-order periodic response of the balanced state to gravity (one plane, constant speed)


def gravity_perturbation(dr, out_json):
    """Constant speed Omega, one plane, gravity g_s small against r Omega^2.  The balanced state
    (3.14) (D at rest, balls at psi*) plus the static offset solves the equations with gravity except
    for the balls' tangential weight -m g_s r cos(Omega t + psi*), a 1X force in the rotating frame.
    First order in eps = g_s/(r Omega^2): psi_i = psi_i* + a_i cos(Omega t) + b_i sin(Omega t),
    q = q_s + q_c cos(2 Omega t) + q_s2 sin(2 Omega t) (the balls' oscillating unbalance is a 0X + 2X
    load in the fixed axes; the 0X part has s'' = 0); harmonic balance of the linearized equations,
    solved by least squares on 24 time samples per revolution: the residual is zero (to rounding) for
    the isotropic default rotor, so the ansatz is exact at first order.  The mean of psi_i - psi_i*
    is zero at first order (the shift of the balanced angles is O(eps^2))."""
    t = dr.t
    planes = [dr.Plane(1, 2)]
    mdl = make_model(dr, planes, gravity=True)
    eq_q, eq_b, _ = mdl.equations()
    p = planes[0]
    omega = F(500)
    par, pdata = params_for(dr, mdl, False)
    gval = F(G_STD)
    # balanced angles (3.14) for two equal balls: cos psi = -m0 r0/(2 m r), psi_1 = -psi_2
    s0 = par[p.m0] * par[p.r0]
    mr = par[p.m[0]] * par[p.r[0]]
    psistar = [sp.acos(-s0 / (2 * mr)), -sp.acos(-s0 / (2 * mr))]
    Wt = sp.Symbol('Wt', real=True)     # Omega t
    A = sp.symbols('a1 b1 a2 b2', real=True)
    Cq = sp.symbols('xc xs yc ys ac as bc bs', real=True)
    Wtot = dr.M_ + p.m0 + sum(p.m)
    Dm = p.d * (p.m0 + sum(p.m))
    offs = static_offset(dr, mdl, Wtot, Dm)
    ansatz = {}
    qfun = [dr.x, dr.y, dr.al, dr.be]
    eps1 = sp.Symbol('e1')               # bookkeeping: first order
    for k, f in enumerate(qfun):
        ansatz[f] = offs[k] + eps1 * (Cq[2 * k] * sp.cos(2 * omega * t) + Cq[2 * k + 1] * sp.sin(2 * omega * t))
    for i in range(2):
        ansatz[p.phi[i]] = omega * t + psistar[i] + eps1 * (A[2 * i] * sp.cos(omega * t) + A[2 * i + 1] * sp.sin(omega * t))
    ansatz[dr.ph0] = omega * t
    res = []
    for e in eq_q + eq_b:
        ee = e.subs(ansatz).doit()                  # the static offset carries g_s too
        ee = ee.subs(g_s, eps1 * g_s).subs(par).subs(g_s, gval)
        z0 = ee.subs(eps1, 0)
        for kk in range(3):
            assert abs(z0.subs(t, F(kk) / 7).evalf(PREC)) < 1e-20, 'balanced state is not a solution at g = 0'
        res.append(sp.expand(ee.diff(eps1).subs(eps1, 0)))
    # samples of one revolution (period 2 pi / Omega)
    rows, rhs = [], []
    unknown = list(A) + list(Cq)
    ns = 24
    for e in res:
        for kk in range(ns):
            tv = F(2) * sp.pi * kk / (ns * omega)
            ev = e.subs(t, tv).evalf(PREC)
            rows.append([ev.diff(u) for u in unknown])
            rhs.append(-ev.subs({u: 0 for u in unknown}))
    Am = sp.Matrix(rows)
    bv = sp.Matrix(rhs)
    sol = (Am.T * Am).LUsolve(Am.T * bv)
    resid = max(abs(v) for v in (Am * sol - bv))
    scale = max(abs(v) for v in bv)
    assert resid <= 1e-20 * scale, 'harmonic balance residual %s (scale %s)' % (resid, scale)
    sold = dict(zip(unknown, sol))
    epsv = gval / (par[p.r[0]] * omega**2)
    # decoupled ball (D held at rest): m r^2 psi'' + h r^2 psi' = -m g_s r cos(Omega t + psi*)
    dec = []
    hm = par[p.h[0]] / par[p.m[0]]
    for i in range(2):
        z = gval / par[p.r[i]] * sp.exp(sp.I * psistar[i]) / (omega**2 - sp.I * omega * hm)
        # psi1 = Re(z e^{i Omega t}) = Re z cos - Im z sin
        dec.append((sp.re(z).evalf(PREC), (-sp.im(z)).evalf(PREC)))
    for i in range(2):
        amp = sp.sqrt(sold[A[2 * i]]**2 + sold[A[2 * i + 1]]**2)
        ampd = sp.sqrt(dec[i][0]**2 + dec[i][1]**2)
        assert abs(amp / ampd - 1) < 0.05, 'perturbation amplitude vs decoupled ball: %s %s' % (amp, ampd)
    _say('check: gravity, first-order 1X response of the balanced state (one plane, Omega = 500 rad/s): '
         'harmonic balance exact (residual %.1e of the forcing), ball amplitudes %.6e, %.6e rad '
         '(eps = g_s/(r Omega^2) = %.4e; decoupled ball %.6e): OK'
         % (float(resid / scale), float(sp.sqrt(sold[A[0]]**2 + sold[A[1]]**2)),
            float(sp.sqrt(sold[A[2]]**2 + sold[A[3]]**2)), float(epsv),
            float(sp.sqrt(dec[0][0]**2 + dec[0][1]**2))))
    out_json['perturbation'] = fl({
        'Omega': omega, 'g_s': gval, 'theta': sp.pi / 2, 'eps': epsv, 'psi_star': psistar,
        'psi_cos': [sold[A[0]], sold[A[2]]], 'psi_sin': [sold[A[1]], sold[A[3]]],
        'psi_cos_decoupled': [dec[0][0], dec[1][0]], 'psi_sin_decoupled': [dec[0][1], dec[1][1]],
        'static_offset': [sp.sympify(v).subs(par).subs(g_s, gval).evalf(PREC) for v in offs],
        'q_cos2': [sold[Cq[0]], sold[Cq[2]], sold[Cq[4]], sold[Cq[6]]],
        'q_sin2': [sold[Cq[1]], sold[Cq[3]], sold[Cq[5]], sold[Cq[7]]],
        'note': 'one_plane parameters, horizontal shaft, constant Omega (phi_0 = Omega t); first order in eps: '
                'psi_i(t) = psi_star_i + psi_cos_i cos(Omega t) + psi_sin_i sin(Omega t), q(t) = static_offset '
                '+ q_cos2 cos(2 Omega t) + q_sin2 sin(2 Omega t) (q = x, y, alpha, beta); mean shift O(eps^2)'})


# ----------------------------------------------------------------------------------------------
# 3. Rolling resistance and stiction


def resistance_force(dr, p, i, f):
    """Generalized force of rolling resistance f N against the relative motion, moved to the
    left-hand side of the ball equation: + r f N sgn(psi')  (it acts on the rotor only through the
    motor's phi_0 equation, with the opposite sign: - r f N sgn(psi'))."""
    return p.r[i] * f * N_fixed(dr, p, i)


def stuck_checks(dr, planes, mdl_full, stuck_model, c):
    """The constrained (stuck) model's equations equal the full ones with phi = phi_0 + c imposed,
    the stuck ball's equation being the holding force: eq_0(stuck) = eq_0 + eq_ball."""
    p = planes[0]
    f = p.phi[0]
    t = dr.t
    full_q, full_b, full_0 = mdl_full.equations()
    st_q, st_b, st_0 = stuck_model.equations()

    def impose(e):
        for a, b in [(f.diff(t, 2), dr.Om.diff(t)), (f.diff(t), dr.Om), (f, dr.ph0 + c)]:
            e = e.subs(a, b)
        return e.doit()
    for a, b in zip(st_q, full_q):
        assert sp.simplify(sp.expand(a - impose(b))) == 0, 'stuck: rotor equation'
    for a, b in zip(st_b, full_b[1:]):
        assert sp.simplify(sp.expand(a - impose(b))) == 0, 'stuck: other balls'
    d = sp.simplify(sp.expand(st_0 - impose(full_0 + full_b[0])))
    assert d == 0, 'stuck: phi_0 equation = phi_0 + ball equations: %s' % d
    # holding force: H = (ball residual)/r with the ball stuck
    H = impose(full_b[0]) / p.r[0]
    Hh = p.m[0] * (p.r[0] * dr.Om.diff(t) - dr.u_D(p.d).diff(t, 2) * sp.sin(dr.ph0 + c)
                   + (dr.v_D(p.d).diff(t, 2) + g_s) * sp.cos(dr.ph0 + c))
    assert sp.simplify(sp.expand(H - Hh)) == 0, 'holding force'
    return H, impose(N_fixed(dr, p, 0))


# ----------------------------------------------------------------------------------------------
# 5. Impact


def mass_matrix(dr, c, motor):
    """Generalized mass matrix (Hessian of T in the velocities) and the linear part b at the state."""
    T = c.sym(c.model.T)
    vels = c.vel[:4] + ([c.vel[4]] if motor else []) + c.vel[5:]
    Mm = sp.Matrix(len(vels), len(vels), lambda a, b: T.diff(vels[a]).diff(vels[b]))
    bl = sp.Matrix([T.diff(v) for v in vels]) - Mm * sp.Matrix(vels)
    return Mm.xreplace(c.s).evalf(PREC), bl.xreplace(c.s).evalf(PREC), vels


def impact_case(dr, model, two_planes, motor, pair_plane, e):
    """Balls 1 and 2 of plane pair_plane in contact (ball 2 ahead by the gap angle), approaching."""
    pl = model.planes[pair_plane - 1]
    _, pdata = params_for(dr, model, two_planes)
    r = pdata[pair_plane - 1]['r'][0]
    delta = 2 * F(RHO)
    gap = 2 * sp.asin(delta / (2 * r))                 # (delta_i + delta_j)/2 = delta, / (2r)
    ps1 = pdata[pair_plane - 1]['psi'][0]
    rates = pdata[pair_plane - 1]['rate']
    ahead = 1 if rates[1] < rates[0] else -1          # ball 2 ahead of ball 1 iff they approach that way
    c = Case(dr, model, two_planes, motor, psi={(pair_plane, 1): F(ps1) + ahead * gap})
    Mm, bl, vels = mass_matrix(dr, c, motor)
    v0 = sp.Matrix([c.s[v] for v in vels])
    n = len(vels)
    ki = vels.index(c.vel[5 + model.phis.index(pl.phi[0])])
    kj = vels.index(c.vel[5 + model.phis.index(pl.phi[1])])
    Jr = sp.zeros(1, n)
    Jr[ki], Jr[kj] = -ahead, ahead             # gap coordinate: +-(phi_2 - phi_1), ball ahead minus ball behind
    Minv_Jt = Mm.LUsolve(Jr.T)
    G = (Jr * Minv_Jt)[0]
    u = (Jr * v0)[0]                                   # rate of the gap (negative: approaching)
    assert u < 0
    Lam = -(1 + F(e)) * u / G
    v1 = v0 + Minv_Jt * Lam
    T = lambda v: (v.T * Mm * v / 2)[0] + (bl.T * v)[0]      # T up to its velocity-free part
    dT = T(v1) - T(v0)
    loss = F(0.5) * (1 - F(e)**2) * u**2 / G
    work = (bl.T * (v1 - v0))[0]                            # prescribed: Omega * (drive impulse)
    scale = u**2 / G                                        # twice the largest possible loss
    if motor:
        assert abs(dT + loss) <= 1e-22 * scale, 'impact energy (motor): %s %s' % (dT, loss)
    else:
        assert abs(dT + loss - work) <= 1e-22 * (scale + abs(work)), 'impact energy (prescribed): %s %s %s' % (dT, loss, work)
    assert abs((Jr * v1)[0] + F(e) * u) <= 1e-25 * abs(u)
    # generalized momenta: all unchanged except p_i, p_j, whose sum is unchanged
    dp = Mm * (v1 - v0)
    for k in range(n):
        if k not in (ki, kj):
            assert abs(dp[k]) < 1e-25
    assert abs(dp[ki] + dp[kj]) < 1e-25
    # pair-only limit: rotor velocities held, k = 1
    mi, mj = c.s[pl.m[0]], c.s[pl.m[1]]
    mu = mi * mj / (mi + mj) * F(r)**2
    w1 = c.s[c.vel[5 + model.phis.index(pl.phi[0])]]
    w2 = c.s[c.vel[5 + model.phis.index(pl.phi[1])]]
    u12 = w2 - w1
    Ppair = mi * w1 + mj * w2
    if motor:
        assert abs(bl.norm()) < 1e-25, 'motor: T has no linear velocity terms'
    names = [str(v).replace('_d', '') + '_d' for v in vels]
    return dict(e=e, gap_angle=gap, psi=[F(ps1), F(ps1) + ahead * gap],
                rate=[c.ballstate[(pair_plane, 0)][1], c.ballstate[(pair_plane, 1)][1]],
                relative_speed_before=u, impulse=Lam, G=G, reduced_inertia=1 / G,
                velocities_after=dict(zip(names, list(v1))), energy_change=dT, impact_loss=loss,
                drive_work=(None if motor else work),
                pair_only_reduced_inertia=mu,
                pair_only_rates_after=[(Ppair + mj * F(e) * u12) / (mi + mj), (Ppair - mi * F(e) * u12) / (mi + mj)])


def resting_contact(dr, planes, gval):
    """Balls 1, 2 of plane 1 touching (phi_2 = phi_1 + gap): one body; the contact force lambda
    (generalized, on phi_2; compressive when lambda > 0) from ball 2's equation."""
    t = dr.t
    p = planes[0]
    gap = sp.Symbol('gamma', positive=True)
    full = make_model(dr, planes, gravity=True)
    fq, fb, f0 = full.equations()
    one = dr.Model(planes)
    one.V = full.V
    f2 = p.phi[1]
    sub = [(f2.diff(t, 2), p.phi[0].diff(t, 2)), (f2.diff(t), p.phi[0].diff(t)), (f2, p.phi[0] + gap)]
    for attr in ('T', 'V', 'R', 'R_balls'):
        ex = getattr(one, attr)
        for a, b in sub:
            ex = ex.subs(a, b)
        setattr(one, attr, ex)
    one.phis = [g for g in one.phis if g != f2]
    one.balls = [(pp, ii) for pp, ii in one.balls if not (pp is p and ii == 1)]
    oq, ob, o0 = one.equations()

    def impose(e):
        for a, b in sub:
            e = e.subs(a, b)
        return e.doit()
    for a, b in zip(oq, fq):
        assert sp.simplify(sp.expand(a - impose(b))) == 0, 'resting contact: rotor equation'
    assert sp.simplify(sp.expand(ob[0] - impose(fb[0] + fb[1]))) == 0, 'resting contact: pair equation'
    assert sp.simplify(sp.expand(o0 - impose(f0))) == 0
    _say('check: resting contact: the pair as one body (phi_2 = phi_1 + gap) gives the rotor equations and '
         'pair equation = ball 1 + ball 2 equations with the constraint imposed: OK')
    lam = impose(fb[1])
    c = Case(dr, one, False, False, extra={g_s: gval})      # one plane, prescribed speed
    par, _ = params_for(dr, one, False)
    gv = 2 * sp.asin(2 * F(RHO) / (2 * par[p.r[0]]))
    c.s[gap] = gv
    # ball 2 rides with ball 1: rate of ball 1 is its check-state rate
    acc = c.solve(oq, ob, o0)
    out = {'gap_angle': gv, 'accelerations': acc, 'lambda': c.value(lam.subs(gap, gv)),
           'g_s': gval, 'note': 'one_plane parameters and state, prescribed speed, gravity on; ball 12 at '
                                'phi_11 + gap_angle with the same rate as ball 11; lambda = generalized contact '
                                'force on phi_12 (N m), compressive if > 0'}
    return out


# ----------------------------------------------------------------------------------------------


def run(dr):
    results = {}
    gval = F(G_STD) * sp.sin(F(THETA))
    z1 = derive_gravity_potential(dr)
    _say('note: the axial weight g cos(theta) would add m g cos(theta) (%s) per small mass; dropped '
         '(the model keeps the in-plane component only)' % z1)
    grav = {'g': G_STD, 'theta': THETA, 'g_s': float(gval),
            'note': 'g_s = g sin(theta) along -y; parameters and state as one_plane / two_planes (planes1 / planes2); '
                    'accelerations with gravity; *_N: normal force of each ball at that state (N)'}
    normal = {'g_s': float(gval)}
    rolling_res = {'f': F_ROLL, 'g_s': float(gval)}
    stick = {'g_s': float(gval)}
    rollin = {'rho': RHO}
    impact = {'e': E_REST, 'delta': 2 * RHO}
    derive_normal_force(dr)
    for name, nballs in (('planes1', [2]), ('planes2', [2, 2])):
        two = name == 'planes2'
        planes = [dr.Plane(j + 1, n) for j, n in enumerate(nballs)]
        m0 = make_model(dr, planes)
        mg = make_model(dr, planes, gravity=True)
        eqg, Wtot, Dm = check_gravity_terms(dr, m0, mg)
        _say('check (%s): gravity adds exactly g_s (M + sum m) to y, -g_s sum d m to alpha, m g_s r cos(phi) '
             'to each ball, g_s sum m_0 r_0 cos(theta_j) to phi_0; g_s = 0 gives the old equations: OK' % name)
        dr.check_energy_identity(mg, *eqg)
        _say('check (%s): energy identity with gravity (E = T + V including the weights): OK' % name)
        offs = static_offset(dr, mg, Wtot, Dm)
        _say('check (%s): static offset = closed form (x = beta = 0): OK' % name)
        grav[name] = fl(gravity_numbers(dr, mg, eqg, offs, two, gval))
        _say('check (%s): gravity check values, energy balance at the state (1e-12): OK' % name)
        # normal force without gravity (the model of rotor.md / the prescribed drive)
        nb = {}
        for motor in (False, True):
            c = Case(dr, m0, two, motor, extra={g_s: 0})
            c.solve(*m0.equations())
            nb['motor' if motor else 'prescribed'] = fl(normal_forces(dr, c))
        normal[name] = {'no_gravity': nb,
                        'gravity': {k: grav[name][k + '_N'] for k in ('prescribed', 'motor')}}
        # rolling resistance f N sgn(psi'), gravity on
        rr = {}
        for motor in (False, True):
            c = Case(dr, mg, two, motor, extra={g_s: gval})
            extra = []
            for p, i in mg.balls:
                sgn = 1 if c.ballstate[(p.j, i)][1] > 0 else -1
                extra.append(sgn * resistance_force(dr, p, i, F(F_ROLL)))
            q_, b_, z_ = eqg
            z_extra = -sum(extra, sp.Integer(0))      # the reaction on the rotor (phi_0 equation)
            acc = c.solve(q_, b_, z_ + z_extra, extra_b=extra)
            # power of the resistance forces: - sum r f N |psi'|
            P_res = -sum(abs(c.value(e)) * abs(c.ballstate[(p.j, i)][1]) for e, (p, i) in zip(extra, mg.balls))
            eb = c.energy_balance(z_ + z_extra, extra_power=P_res)
            rr['motor' if motor else 'prescribed'] = fl({'accelerations': acc, 'N': normal_forces(dr, c),
                                                         'resistance_power': P_res, 'dE_dt': eb['dE_dt']})
        rolling_res[name] = rr
        _say('check (%s): rolling resistance f N (implicit in the accelerations through N), energy balance '
             'with the resistance power - sum r f N |psi\'|: OK' % name)
        # stiction: ball 1 of plane 1 stuck at its check-state angle
        cpsi = sp.Symbol('c_11', real=True)
        ms = make_model(dr, planes, gravity=True, stuck=[(planes[0], 0, cpsi)])
        H, Nst = stuck_checks(dr, planes, mg, ms, cpsi)
        _say('check (%s): stuck ball = mass fixed to the rotor: constrained equations = full ones with '
             'phi_11 = phi_0 + c, phi_0 equation = phi_0 + ball equations; holding force H = m (r Omega\' '
             '- u_D\'\' sin phi + (v_D\'\' + g_s) cos phi): OK' % name)
        sh = {}
        for motor in (False, True):
            c = Case(dr, ms, two, motor, extra={g_s: gval})
            c.s[cpsi] = c.ballstate[(1, 0)][0]
            acc = c.solve(*ms.equations())
            eb = c.energy_balance(ms.equations()[2])
            Hv, Nv = c.value(H), c.value(Nst)
            sh['motor' if motor else 'prescribed'] = fl({'accelerations': acc, 'H': Hv, 'N': Nv,
                                                         'ratio': abs(Hv) / Nv, 'dE_dt': eb['dE_dt']})
        sh['note'] = 'ball phi_11 stuck at psi = its check-state psi (psi\' = 0); the other balls free; gravity on'
        stick[name] = sh
        # rolling inertia (no gravity): rho for every ball
        rho = {(p, i): sp.Symbol('rho_%d%d' % (p.j, i + 1), positive=True) for p, i in m0.balls}
        mr = make_model(dr, planes, rho=rho)
        eqr = mr.equations()
        for (p, i), e_r, e_0 in zip(m0.balls, eqr[1], m0.equations()[1]):
            extra_t = sp.Rational(2, 5) * p.m[i] * p.r[i] * (p.r[i] * p.phi[i].diff(dr.t, 2)
                                                             - (p.r[i] + rho[(p, i)]) * dr.Om.diff(dr.t))
            assert sp.simplify(sp.expand(e_r - e_0 - extra_t)) == 0, 'rolling inertia term'
        dr.check_energy_identity(mr, *eqr)
        ri = {}
        for motor in (False, True):
            ex = {s: F(RHO) for s in rho.values()}
            ex[g_s] = 0
            c = Case(dr, mr, two, motor, extra=ex)
            acc = c.solve(*eqr)
            eb = c.energy_balance(eqr[2])
            ri['motor' if motor else 'prescribed'] = fl({'accelerations': acc, 'energy': eb['energy'],
                                                         'dE_dt': eb['dE_dt']})
        rollin[name] = ri
        _say('check (%s): rolling inertia adds (2/5) m r (r phi\'\' - (r + rho) Omega\') to each ball equation; '
             'energy identity and balance hold: OK' % name)
        # impact (no gravity, no rolling inertia): pair in the last plane
        im = {}
        for motor in (False, True):
            for e in (E_REST, 1.0):
                key = ('motor' if motor else 'prescribed') + ('_e1' if e == 1.0 else '')
                im[key] = fl(impact_case(dr, m0, two, motor, len(planes), e))
        impact[name] = im
        _say('check (%s): impact: restitution on phi_j\' - phi_i\', momenta conjugate to all other coordinates '
             'and p_i + p_j unchanged, energy change = -(1/2)(1 - e^2) u^2/G (+ drive work Omega dp_0, prescribed): OK'
             % name)
        if name == 'planes1':
            impact['resting_contact'] = fl(resting_contact(dr, planes, gval))
    rolling_kinematics_check(dr)
    gravity_perturbation(dr, grav)
    impact['note'] = ('balls 1, 2 of the last plane touching (psi_2 = psi_1 + gap_angle, gap_angle = 2 asin(delta/(2r)) '
                      'for equal diameters delta), rates of the check state (approaching), other state as '
                      'one_plane / two_planes, no gravity; G = J M^-1 J^T with J = (-1 at phi_i, +1 at phi_j); '
                      'velocities_after of all coordinates; *_e1: e = 1')
    stick['mu_needed_note'] = 'the ball stays stuck while |H| <= mu N, i.e. mu >= ratio'
    results['gravity'] = grav
    results['normal_force'] = normal
    results['rolling_resistance'] = fl(rolling_res)
    results['stiction_holding'] = stick
    results['rolling_inertia'] = rollin
    results['impact'] = fl(impact)
    return results


def rolling_kinematics_check(dr):
    """Relative inertia of a rolling ball: coefficient of psi'^2 is 7/10 m r^2 exactly (factor 7/5);
    the rotating-frame equation (7/5) m r^2 psi'' + m r^2 (1 - 2 rho/(5 r)) Omega' + h r^2 psi' = ..."""
    t = dr.t
    m, r, rho = sp.symbols('m r rho', positive=True)
    ph = sp.Function('phi', real=True)(t)
    Tr = rolling_energy(dr, m, r, rho, ph)
    assert sp.simplify(Tr - sp.Rational(1, 5) * m * ((r + rho) * dr.Om - r * ph.diff(t))**2) == 0
    psid = sp.Symbol('psid')
    Ttot = sp.expand((sp.Rational(1, 2) * m * r**2 * ph.diff(t)**2 + Tr).subs(ph.diff(t), dr.Om + psid))
    coef = Ttot.coeff(psid, 2)
    assert sp.simplify(coef - sp.Rational(7, 10) * m * r**2) == 0
    # equation of phi from T_trans + T_rot, in the rotating frame
    e = (sp.Rational(1, 2) * m * r**2 * ph.diff(t)**2 + Tr).diff(ph.diff(t)).diff(t)
    psi = sp.Function('psi', real=True)(t)
    e = e.subs(ph, dr.ph0 + psi).doit()
    want = sp.Rational(7, 5) * m * r**2 * psi.diff(t, 2) + m * r**2 * (1 - 2 * rho / (5 * r)) * dr.Om.diff(t)
    assert sp.simplify(sp.expand(e - want)) == 0
    _say('check: rolling ball on the outer race: T_rot = (1/5) m ((r + rho) Omega - r phi\')^2, relative inertia '
         '7/5 of the point mass exactly (no rho/r term), Euler term m r^2 (1 - 2 rho/(5 r)) Omega\': OK')
