#!/usr/bin/env python3
"""When does the surface of the lava lake freeze, and how hot is the bulk then?

A column of particles (spacing dx) through the lake at the gate, depth H, insulated floor,
conducting heat (diffusivity kappa/(rho cv)) and cooling at its top particle by Eq 25,
dT/dt = -kT T (T_air = 0). Prints, for each kT, when the 1st, 2nd and 3rd particle from the top
fall below 500 C, and the mid-depth, bottom and mean temperatures at that moment.
Python 3 standard library only: python3 crust_time.py
"""
kappa, rho, cv, dx, H = 1.0, 2000.0, 1.0, 0.025, 0.45
alpha = kappa / (rho * cv)
n = int(round(H / dx))
for kT in (0.02, 0.05, 0.1, 0.2, 0.5):
    T = [1000.0] * n
    dt, t, found = 0.05, 0.0, {}
    while t < 1500.0 and len(found) < 3:
        lap = [(T[i - 1] - T[i] if i > 0 else 0.0) + (T[i + 1] - T[i] if i < n - 1 else 0.0) for i in range(n)]
        T = [T[i] + dt * alpha / dx**2 * lap[i] - (dt * kT * T[0] if i == 0 else 0.0) for i in range(n)]
        t += dt
        for k in (1, 2, 3):
            if k not in found and T[k - 1] < 500.0:
                found[k] = f"{t:5.0f} s (mid {T[n // 2]:4.0f} C, bottom {T[-1]:4.0f} C, mean {sum(T) / n:4.0f} C)"
    print(f"kT = {kT}:")
    for k in sorted(found):
        print(f"  particle {k} from the top below 500 C at {found[k]}")
