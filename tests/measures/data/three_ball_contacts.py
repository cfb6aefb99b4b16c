#!/usr/bin/env python3
"""Contact areas of three balls by mpmath quadrature (50 digits), for
test_contact_enclosure: an independent check of the cell measures'
contact enclosures where a third ball cuts the face.

For atom i (centre ci, radius Ri, expanded radius r = Ri + probe) and
neighbour j (d = cj - ci, D = |d|, delta = Rj - Ri, N = D^2 - delta^2), the
face i|j lies at t = N / (2 q) along the direction u, q = u.d + delta, with
area element t^2 sqrt(N + 2 delta q) / q per solid angle (cell_patches.c),
a function f(z) of z = u.e (e = d / D) alone. The face lies inside the
expanded balls where t <= r, i.e. z >= (N / (2 r) - delta) / D, and j owns
the direction against a third ball k where N_k (u.d_j + delta_j) >=
N_j (u.d_k + delta_k), linear in u. With u = z e + s (cos p a + sin p b),
s = sqrt(1 - z^2), that reads A(z) >= N_j s rho cos(p - p0), rho the part
of d_k across e, so the azimuth owned at z has the length L(z) = 2 pi,
0 or 2 pi - 2 acos(A / (N_j s rho)), and the area is the integral over z of
f(z) L(z), taken by tanh-sinh quadrature between the breakpoints where
A^2 = (N_j rho)^2 (1 - z^2) (the roots of a quadratic).

Writes on stdout each case's balls ('ball case x y z r', the XYZR texts
below) and areas ('area case i j value', 30 digits; probe 1.4):
three_ball_contacts.txt.
"""
import mpmath as mp

mp.mp.dps = 50
PROBE = mp.mpf("1.4")
CASES = {
    "unequal": "0 0 0 1.7\n3.0 0 0 1.52\n1.4 2.6 0.3 1.55\n",
    "equal": "0 0 0 1.7\n3.2 0 0 1.7\n1.5 2.7 0.5 1.7\n",
    "mixed": "0 0 0 1.8\n2.9 0.4 0 1.2\n1.0 -2.5 1.1 1.52\n",
    "tight": "0 0 0 1.55\n2.1 0.3 0.2 1.7\n0.9 1.8 -0.4 1.52\n",
}


def balls(text):
    out = []
    for line in text.strip().splitlines():
        x, y, z, r = (mp.mpf(v) for v in line.split())
        out.append((mp.matrix([x, y, z]), r))
    return out


def contact(b, i, j, k):
    ci, Ri = b[i]
    r = Ri + PROBE
    d = b[j][0] - ci
    dk = b[k][0] - ci
    D = mp.norm(d)
    dl, dlk = b[j][1] - Ri, b[k][1] - Ri
    N, Nk = D**2 - dl**2, mp.norm(dk) ** 2 - dlk**2
    e = d / D
    pk = (e.T * dk)[0]
    rho = mp.norm(dk - pk * e)
    zmin = (N / (2 * r) - dl) / D
    if zmin >= 1:
        return mp.mpf(0)
    zmin = max(zmin, mp.mpf(-1))

    def A(z):
        return Nk * (D * z + dl) - N * (z * pk + dlk)

    def L(z):
        s = mp.sqrt(max(1 - z * z, 0))
        den = N * s * rho
        if den == 0:
            return 2 * mp.pi if A(z) >= 0 else mp.mpf(0)
        c = A(z) / den
        if c >= 1:
            return 2 * mp.pi
        if c <= -1:
            return mp.mpf(0)
        return 2 * mp.pi - 2 * mp.acos(c)

    def f(z):
        q = D * z + dl
        return N**2 * mp.sqrt(N + 2 * dl * q) / (4 * q**3) * L(z)

    # A(z)^2 - (N rho)^2 (1 - z^2) = 0: a z^2 + b z + c
    a1, a0 = Nk * D - N * pk, Nk * dl - N * dlk
    qa, qb, qc = a1**2 + (N * rho) ** 2, 2 * a1 * a0, a0**2 - (N * rho) ** 2
    pts = [zmin, mp.mpf(1)]
    disc = qb**2 - 4 * qa * qc
    if disc > 0:
        for z in ((-qb - mp.sqrt(disc)) / (2 * qa), (-qb + mp.sqrt(disc)) / (2 * qa)):
            if zmin < z < 1:
                pts.append(z)
    pts.sort()
    return mp.quad(f, pts)


def main():
    for name, text in CASES.items():
        for line in text.strip().splitlines():
            print("ball", name, line)
        b = balls(text)
        for i in range(3):
            for j in range(3):
                if i < j:
                    k = 3 - i - j
                    a = contact(b, i, j, k)
                    if a > 0:
                        print("area", name, i, j, mp.nstr(a, 30))


if __name__ == "__main__":
    main()
