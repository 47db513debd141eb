#!/usr/bin/python3
"""sky-below-mc.py - why the sky map holds a radiance below the horizon (docs/architecture.md,
src/optics/sky.h): a Monte-Carlo estimate of the sky a rough sea reflects towards a grazing
view, against the lobe eq. 27 filters (Bruneton 2010), with rays reflected below the horizon
taking either the horizon's radiance (swell before) or the average Fresnel reflectance times
the sky irradiance over pi (Bruneton §6's multiple reflections, swell now).

The reference weights each facet by its projected area towards the viewer, max(v.n, 0) / n_z
(facets turned away are hidden), and gives a ray reflected below the horizon the §6 radiance;
eq. 27's lobe is the Gaussian of slopes unweighted. Isotropic slopes of variance VAR per axis,
a synthetic sky brightening towards the horizon, L(e) = 0.3 + 0.7 exp(-e / 8 deg). Needs numpy.
"""
import numpy as np

F_AVG = 0.066                      # sky.c sky_fresnel_avg at n = 1.333


def sky(e):
    return 0.3 + 0.7 * np.exp(-np.degrees(e) / 8.0)


def main():
    rng = np.random.default_rng(1)
    mu = np.linspace(0.0, 1.0, 20001)[1:]
    e_pi = 2.0 * np.trapz(sky(np.arcsin(mu)) * mu, mu)       # E / pi
    below = F_AVG * e_pi
    n_s = 400000
    print("sky: horizon %.3f, E/pi %.3f, below the horizon %.4f" % (sky(0.0), e_pi, below))
    for var in (0.01, 0.04):
        s = rng.normal(0.0, np.sqrt(var), (n_s, 2))
        n = np.stack([-s[:, 0], -s[:, 1], np.ones(n_s)], 1)
        n /= np.linalg.norm(n, axis=1)[:, None]
        for dep in (5, 10, 20, 40):
            d = np.radians(dep)
            v = np.array([-np.cos(d), 0.0, np.sin(d)])       # towards the eye
            vn = n @ v
            r = 2.0 * vn[:, None] * n - v
            el = np.arcsin(np.clip(r[:, 2], -1.0, 1.0))
            up = r[:, 2] > 0.0
            l_new = np.where(up, sky(np.maximum(el, 0.0)), below)
            l_old = sky(np.maximum(el, 0.0))
            w = np.maximum(vn, 0.0) / n[:, 2]
            ref = (w * l_new).sum() / w.sum()
            new, old = l_new.mean(), l_old.mean()
            print("slope variance %.2f, view %2d deg below the level: reference %.3f; eq. 27's "
                  "lobe with the sky below the horizon %.3f (%+.0f %%), with the horizon's %.3f "
                  "(%+.0f %%); the lobe's share below %.2f" %
                  (var, dep, ref, new, 100.0 * (new / ref - 1.0), old,
                   100.0 * (old / ref - 1.0), 1.0 - up.mean()))


if __name__ == "__main__":
    main()
