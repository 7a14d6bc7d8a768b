"""The Fig. 11 setup of Patel et al. 2013 as this project draws it (paper_figs/patel_fig11.py,
scripts/gpu_fig11.sh): the contract example's disk (radius 0.5, 1 above a white receiver;
d1 = d = 1) under a light of mean (0.3, -0.1) and covariance var I, slab spacing 0.01. No
third-party imports, so the GPU script needs Python alone."""

LOW_VAR, HIGH_VAR = 0.004, 0.06


def scene(var, resolution=128):
    return {
        "camera": {"projection": "orthographic", "eye": [0, 0, 2], "target": [0, 0, 0], "up": [0, 1, 0],
                   "height": 3.0, "resolution": [resolution, resolution]},
        "render": {"slab_spacing": 0.01, "d1": 1.0, "seed": 11},
        "lights": [{"mean": [0.3, -0.1], "cov": [[var, 0], [0, var]]}],
        "materials": {"black": {"color": [0, 0, 0]}, "white": {}},
        "objects": [{"shape": "disk", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 0.5, "material": "black"},
                    {"shape": "rect", "center": [0, 0, -1], "normal": [0, 0, 1], "size": [3, 3], "material": "white"}],
    }
