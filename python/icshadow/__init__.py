"""icshadow: convolution soft shadows (Patel et al. 2013) from Python, over the project's C
libraries (libicshadow, libicshadow_render): the numerics over numpy arrays, LUTs, lights files
and light fitting, the isolines of the shadow behind an edge, and scenes planned, rendered and
compared with the Monte-Carlo reference.
docs/python.md."""
from ._lib import Error
from .exr import read_exr, srgb, write_exr, write_png
from .lights import Light, fit_light, lights_json, read_lights, write_lights
from .lut import lut, lut_header
from .numerics import (EllipseKernel, ellint_e, ellint_e_m1, ellint_k, ellint_k_m1,
                       ellipse_kernel, ellipse_ratio, ellipse_ratio_to_t, ellipse_varx,
                       ellipse_vx, ellipse_vy)
from .render import Render, Renderer, backends, compare, default_scene, plan, render
from .theory import Light1D, isoline

__all__ = ["Error", "Light", "fit_light", "lights_json", "read_lights", "write_lights", "lut",
           "lut_header", "EllipseKernel", "ellint_e", "ellint_e_m1", "ellint_k", "ellint_k_m1",
           "ellipse_kernel", "ellipse_ratio", "ellipse_ratio_to_t", "ellipse_varx", "ellipse_vx",
           "ellipse_vy", "Render", "Renderer", "read_exr", "srgb", "write_exr", "write_png", "backends", "compare", "default_scene", "plan", "render", "Light1D", "isoline"]
__version__ = "0.2.0"
