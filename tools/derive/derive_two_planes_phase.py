"""derive_two_planes_phase.py: the structure behind src/analysis/rotor_unbalance2.c (docs/rotor.md
"Every unbalance", two planes), in exact rational arithmetic at one arbitrary parameter point (not all
parameters symbolic: the 4x4 determinant is too large for that here).  The closed two-plane system with
sigma_1, sigma_2 eliminated (rows times L1 L2) is [G H; H~ G*] with H = q1 B1 + q2 B2 (Q_j) and
H~ = r1 B1 + r2 B2 (conj Q_j), q and r taken independent.  Checks, each printed with OK or FAILED:
  - its determinant has only the monomials 1, q1 r1, q2 r2, q1 r2, q2 r1, q1 q2 r1 r2 (rotation
    invariance and rank-one B_j);
  - the coefficient M12 of q1 r2 has real coefficients and equals M21 with conjugated coefficients,
    so Delta16 depends on the relative phase only through cos(arg Q1 conj Q2);
  - the determinant is divisible by (L1 L2)^2 (Delta16 has degree 16).
"""
import sys
import sympy as sp
lam=sp.symbols('lambda')
R=sp.Rational
# random rational parameters (exact)
M,A,C,h,c,hc,cc,ht,ct,w=R(7),R(3,20),R(1,25),R(250),R(250000),R(13),R(4000),R(9),R(5000),R(450)
k1,k2,d1,d2,mb1,mb2=R(10),R(12),R(1,10),R(-3,25),R(1,10),R(2,25)
I=sp.I
P=lam+I*w
K11=M*P**2+h*P+c; K12=-(hc*P+cc); K22=A*P**2+(ht-I*C*w)*P+ct
L1=lam**2+k1*lam; L2=lam**2+k2*lam; Lo=[L2,L1]; d=[d1,d2]; mb=[mb1,mb2]
W2=(lam**2+w**2)**2
G=sp.Matrix([[K11,K12],[K12,K22]])*L1*L2
B=[]
for j in range(2):
    e=sp.Matrix([1,d[j]])
    G=G-P**4*Lo[j]*mb[j]/2*e*e.T
    B.append(W2*Lo[j]/2*e*e.T)
Gs=G.applyfunc(lambda x: sp.expand(x).subs(I,-I))
q1,q2,r1,r2=sp.symbols('q1 q2 r1 r2')
H=q1*B[0]+q2*B[1]; Ht=r1*B[0]+r2*B[1]
Mx=sp.BlockMatrix([[G,H],[Ht,Gs]]).as_explicit()
# the determinant over the polynomial ring QQ(i)[q1, q2, r1, r2, lambda] (DomainMatrix: exact, the same
# polynomial as Matrix.det(method='berkowitz') on expressions, 7 s -> 0.4 s)
from sympy.polys.matrices import DomainMatrix
_dM=DomainMatrix.from_Matrix(Mx)
det=sp.expand(_dM.domain.to_sympy(_dM.det()))
poly=sp.Poly(det,q1,q2,r1,r2)
mons=sorted(poly.monoms())
ok_all = True
def report(name, ok):
    global ok_all
    ok_all &= bool(ok)
    print("two planes phase: %s: %s" % (name, "OK" if ok else "FAILED"))
report("monomials 1, q1 r1, q2 r2, q1 r2, q2 r1, q1 q2 r1 r2 only",
       mons == [(0, 0, 0, 0), (0, 1, 0, 1), (0, 1, 1, 0), (1, 0, 0, 1), (1, 0, 1, 0), (1, 1, 1, 1)])
M12=sp.expand(poly.coeff_monomial(q1*r2))
report("M12 has real coefficients", all(sp.im(cf) == 0 for cf in sp.Poly(M12, lam).all_coeffs()) and M12 != 0)
report("M21 = M12 with conjugated coefficients", sp.expand(M12 - sp.expand(poly.coeff_monomial(q2*r1)).subs(I,-I))==0)
den=sp.expand((L1*L2)**2)
report("divisible by (L1 L2)^2, degree 16",
       sp.div(sp.Poly(sp.expand(det.subs({q1: 1, q2: 2, r1: 3, r2: 5})), lam), sp.Poly(den, lam))[1].is_zero
       and sp.Poly(det, lam).degree() == 24)
sys.exit(0 if ok_all else 1)
