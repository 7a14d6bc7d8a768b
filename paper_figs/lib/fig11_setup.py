"""The Fig. 11 setup of Patel et al. 2013 as this project draws it (paper_figs/patel_fig11.py,
scripts/gpu_fig11.sh): scenes/patel_fig11.json, the contract example's disk (radius 0.5, 1 above
a white receiver; d1 = d = 1) under a light of mean (0.3, -0.1) and covariance var I (the file:
HIGH_VAR), slab spacing 0.01. No third-party imports, so the GPU script needs Python alone."""
from figutil import load_scene

LOW_VAR, HIGH_VAR = 0.004, 0.06


def scene(var, resolution=128):
    """scenes/patel_fig11.json with the light's covariance var I and a resolution x resolution view."""
    s = load_scene("patel_fig11")
    s["camera"]["resolution"] = [resolution, resolution]
    s["lights"][0]["cov"] = [[var, 0], [0, var]]
    return s
