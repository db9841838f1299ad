#!/usr/bin/env python3
"""How closely cushion's Mullins softening eta = 1 - erf((D_max - D)/s)/r follows strain-based damage forms on unloading.

docs/physics.md 5.2 (strain driver). For one unloading from the largest strain e_max = 0.75 of a uniaxial compression
(nominal strain e, l = 1 - e, lateral stretches 1), the best max |eta_form(e) - eta_erf(e)| over a grid of (r, s), for
the drivers D = e (the Biot strain norm ||U - I|| here, cushion's strain_scale > 0), the Green-Lagrange |E33|,
-ln J, and the energy W of a hyperfoam (cushion's default, Ogden-Roxburgh). The forms are the foreign benchmark's
(tests/foreign/foreign_effects.hpp), written here again:
  Qi-Boyce-like       eta = 1 - a tanh(e_max/e_s) (1 - (e/e_max)^p)
  exponential damage  eta = (1 - d(e_max)) / (1 - d(e)), d(e) = d_inf (1 - exp(-e/e_d)): the unloading over the
                      loading curve, which a base fitted to the loading curve takes as its own.
The hyperfoam is scale-set campaign c052's base (mu_i kPa, alpha_i; nu = 0): W = sum 2 mu/alpha^2 (l^alpha - 1 - alpha ln l).
Usage: python3 tools/mullins_shapes.py   (standard library only; about 12 s)
"""
import math

E_MAX = 0.75
STRAINS = [i * E_MAX / 60 for i in range(61)]
HYPERFOAM = [(7.13, 12.84), (0.0263, -4.15), (0.160, 2.98)]  # (mu_kPa, alpha)


def qi_boyce(e, a=0.42, e_s=0.19, p=2.13):
    return 1 - a * math.tanh(E_MAX / e_s) * (1 - (e / E_MAX) ** p)


def exponential_damage(e, d_inf=0.15, e_d=0.29):
    d = lambda x: d_inf * (1 - math.exp(-x / e_d))
    return (1 - d(E_MAX)) / (1 - d(e))


def energy(e):
    l = 1 - e
    return sum(2 * mu / a / a * (l**a - 1 - a * math.log(l)) for mu, a in HYPERFOAM)


DRIVERS = {
    "strain e (Biot)": lambda e: e,
    "Green-Lagrange": lambda e: e - e * e / 2,
    "-ln J": lambda e: -math.log(1 - e),
    "energy W": energy,
}


def best_fit(form, driver):
    """Smallest max |eta error| over r in (1, 11), s over 4.5 decades about the driver's range."""
    d_max = driver(E_MAX)
    best = (math.inf, None)
    for i in range(1, 200):
        r = 1 + 0.05 * i
        for k in range(90):
            s = 1e-3 * d_max * 1.15**k
            err = max(abs(form(e) - (1 - math.erf((d_max - driver(e)) / s) / r)) for e in STRAINS)
            if err < best[0]:
                best = (err, (r, s))
    return best


if __name__ == "__main__":
    forms = {
        "Qi-Boyce-like p 2.13": qi_boyce,
        "Qi-Boyce-like p 1": lambda e: qi_boyce(e, p=1.0),
        "Qi-Boyce-like p 3": lambda e: qi_boyce(e, p=3.0),
        "exponential damage": exponential_damage,
    }
    print("form, then per driver: best max |eta error| (r, s)")
    for name, form in forms.items():
        cells = []
        for dname, driver in DRIVERS.items():
            err, (r, s) = best_fit(form, driver)
            cells.append(f"{dname}: {err:.4f} (r {r:.2f}, s {s:.3g})")
        print(f"{name}: " + "; ".join(cells))
