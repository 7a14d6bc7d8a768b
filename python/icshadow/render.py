"""render.py: scenes (docs/scene-format.md) planned and rendered by libicshadow_render, and renders
compared with a reference (docs/reference.md), from Python. The slab renderer and the Monte-Carlo
reference run in C with the GIL released."""
import json
import os
import threading
import time as time_module
from dataclasses import dataclass, field

import numpy as np

from ._lib import check, ffi, image_from_array, image_to_array, lib, msg_buffer, take_string
from .exr import channels_to_dict, read_exr, write_exr, write_png

AOV_BITS = {"visibility": 1, "depth": 2, "stderr": 4}  # ICS_AOV_VISIBILITY, _DEPTH, _STDERR


def default_scene():
    """The embedded default scene as a dict (`icshadow plan --print-scene`)."""
    return json.loads(ffi.string(lib.ics_scene_default_json()).decode())


def _scene(scene, overrides, allow_outside_paths):
    """(the scene, its name): scene None (the default scene), a path, or a dict (its files
    relative to the working directory). overrides: keys of the scene's "render" object."""
    keep = []  # the C strings the options point to, alive until the scene is made
    opts = ffi.new("ics_scene_opts *")
    opts.allow_outside_paths = 1 if allow_outside_paths else 0
    if overrides:
        keep.append(ffi.new("char[]", json.dumps(overrides).encode()))
        opts.render_json = keep[-1]
    out, msg = ffi.new("ics_scene **"), msg_buffer()
    if isinstance(scene, (str, bytes, os.PathLike)):
        name = os.fsdecode(scene)
        st = lib.ics_scene_create_file_opts(out, os.fsencode(scene), opts, msg, len(msg))
    else:
        if scene is None:
            name, text = "default", ffi.string(lib.ics_scene_default_json())
        elif isinstance(scene, dict):
            name, text = "scene", json.dumps(scene).encode()
        else:
            raise TypeError(f"scene: expected None, a path or a dict, got {type(scene).__name__}")
        st = lib.ics_scene_create_json_opts(out, text, name.encode(), b".", opts, msg, len(msg))
    check(st, msg)
    return ffi.gc(out[0], lib.ics_scene_destroy), name


def _plan_opts(resolution, threads):
    """the plan's options, checked (its renderer NULL: render.model auto planned as blocker)"""
    po = ffi.new("ics_plan_opts *")
    if resolution is not None:
        w, h = resolution
        po.width, po.height = int(w), int(h)
        if po.width < 1 or po.height < 1:
            raise ValueError(f"resolution: expected (width, height) >= 1, got {tuple(resolution)}")
    if int(threads) < 0:
        raise ValueError(f"threads: expected 0 (all cores) or more, got {threads}")
    po.threads = int(threads)
    return po


def _plan(s, po):
    """the plan of scene s with the options po (_plan_opts)"""
    out, msg = ffi.new("ics_plan **"), msg_buffer()
    check(lib.ics_plan_create(out, s, po, msg, len(msg)), msg)
    return ffi.gc(out[0], lib.ics_plan_destroy)


def plan(scene=None, resolution=None, threads=0, allow_outside_paths=False, **overrides):
    """What a render of the scene does and allocates, as `icshadow plan` prints it (a dict:
    passes, omitted passes, memory, active fractions). overrides: keys of the scene's "render"
    object (model="solid", kernel="poisson", samples=4, ...), checked as in a scene file."""
    s, _ = _scene(scene, overrides, allow_outside_paths)
    return json.loads(take_string(lib.icspy_plan_json(_plan(s, _plan_opts(resolution, threads))), "plan"))


@dataclass
class Render:
    """A render: rgba (height, width, 4) float32, row 0 at the top, RGB composited over the
    background and A the accumulated opacity; aovs by name ("light0.V", "Z", "stderr.R", ...),
    each (height, width) float32; summary, the CLI's JSON summary as a dict."""
    rgba: np.ndarray
    aovs: dict = field(default_factory=dict)
    summary: dict = field(default_factory=dict)

    def __getitem__(self, name):
        return self.aovs[name]

    def write_exr(self, path):
        """R, G, B, A and the AOVs as one float EXR with the summary in it, as `icshadow render
        -o` writes them."""
        planes = {c: self.rgba[:, :, k] for k, c in enumerate("RGBA")}
        planes.update(self.aovs)
        write_exr(path, planes, self.summary)

    def write_png(self, path):
        """The 8-bit sRGB preview `icshadow render --png` writes."""
        write_png(path, self.rgba)


def _aov_bits(aovs):
    names = [aovs] if isinstance(aovs, str) else list(aovs or ())
    bits = 0
    for a in names:
        if a not in AOV_BITS:
            raise ValueError(f"aovs: unknown {a!r} (expected {', '.join(AOV_BITS)})")
        bits |= AOV_BITS[a]
    return bits


class Renderer:
    """A backend's renderer kept for many frames, as an application keeps it: its threads, and on
    the cpu backend the memory of its last frame, which the next takes again (no fresh pages:
    docs/renderer.md "The frame's memory kept"). backend, threads, spp, time, noise,
    backend_options: as `render` takes them. It renders one frame at a time (a lock: threads
    sharing one wait for each other). `close()` (or the end of a `with` block) releases it; so
    does the garbage collector."""

    def __init__(self, backend="auto", threads=0, spp=0, time=0.0, noise=0.0, backend_options=None):
        if (spp or time or noise) and backend != "mc":
            raise ValueError("spp, time, noise: only the Monte-Carlo reference takes a stop "
                             f"(backend=\"mc\"; the backend is {backend!r})")
        self.threads = int(threads)
        ro = ffi.new("ics_render_opts *")
        keep = ffi.new("char[]", str(backend).encode())
        ro.backend, ro.threads = keep, self.threads
        ro.spp, ro.time_s, ro.noise = int(spp), float(time), float(noise)
        texts = [ffi.new("char[]", f"{k}={v}".encode()) for k, v in (backend_options or {}).items()]
        option_list = ffi.new("const char *[]", texts + [ffi.NULL])
        if texts:
            ro.options = option_list
        r, msg = ffi.new("ics_renderer **"), msg_buffer()
        check(lib.ics_renderer_create(r, ro, msg, len(msg)), msg)
        self._r = ffi.gc(r[0], lib.ics_renderer_destroy)
        self._lock = threading.Lock()  # the C renderer renders one frame at a time

    @property
    def backend(self):
        """the backend it renders on ("auto" resolved)"""
        return ffi.string(lib.ics_renderer_backend(self._live())).decode()

    def _live(self):
        if self._r is None:
            raise ValueError("this Renderer is closed")
        return self._r

    def close(self):
        """Releases the renderer (its threads and memory) now."""
        with self._lock:
            if self._r is not None:
                ffi.release(self._r)  # its destructor, ics_renderer_destroy, now
                self._r = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def render(self, scene=None, resolution=None, aovs=(), allow_outside_paths=False, **overrides):
        """One frame of a scene (as `render` takes scene, resolution, aovs and overrides), planned
        for this renderer and rendered by it. Returns a Render."""
        with self._lock:
            return self._render(scene, resolution, aovs, allow_outside_paths, overrides)

    def _render(self, scene, resolution, aovs, allow_outside_paths, overrides):
        r = self._live()
        bits = _aov_bits(aovs)
        s, name = _scene(scene, overrides, allow_outside_paths)
        po = _plan_opts(resolution, self.threads)
        t0 = time_module.perf_counter()  # the plan resolves model auto for the renderer
        po.renderer = r
        p = _plan(s, po)
        ms_plan = 1e3 * (time_module.perf_counter() - t0)
        img, ch, msg = ffi.new("ics_image **"), ffi.new("ics_exr_channels **"), msg_buffer()
        stats = ffi.new("ics_render_stats *")
        check(lib.ics_renderer_render_aovs(r, p, bits, img, ch if bits else ffi.NULL, stats, msg,
                                           len(msg)), msg)
        img = ffi.gc(img[0], lib.ics_image_destroy)
        aov = {}
        if bits:
            aov = channels_to_dict(ffi.gc(ch[0], lib.ics_exr_channels_destroy))
        summary = {"scene": name}
        summary.update(json.loads(take_string(lib.icspy_render_summary(p, s, stats, ms_plan),
                                              "render summary")))
        if aov:
            summary["aovs"] = list(aov)
        return Render(image_to_array(img), aov, summary)


def render(scene=None, backend="auto", resolution=None, aovs=(), threads=0, spp=0, time=0.0,
           noise=0.0, allow_outside_paths=False, backend_options=None, **overrides):
    """Renders a scene (None: the default scene; a path; a dict) on a backend ("auto", "cpu",
    "cl", "gl" or "mc", the Monte-Carlo reference; `backends()` lists them) at `resolution`
    (width, height; None: the scene's). aovs: any of "visibility", "depth", "stderr" (mc).
    spp, time, noise: the Monte-Carlo reference's stop (docs/reference.md). backend_options:
    {"cl.device": "1", "gl.context": "egl", "gl.ldi": "device"} (`backends()` lists each
    backend's). overrides: keys of the scene's "render" object (model="solid", ...). Returns a
    Render. One frame on a new renderer: `Renderer` keeps one for many."""
    _aov_bits(aovs)
    _plan_opts(resolution, threads)  # the arguments checked before the renderer starts
    with Renderer(backend, threads, spp, time, noise, backend_options) as r:
        return r.render(scene, resolution, aovs, allow_outside_paths, **overrides)


def _reference(reference):
    """(an ics_image of the reference's R, G, B, its stderr (h, w, 3) or None, its name, its
    summary or {})"""
    if isinstance(reference, Render):
        chans, summary, name = reference.aovs, reference.summary, reference.summary.get("backend", "render")
        rgb = reference.rgba[:, :, :3]
    elif isinstance(reference, (str, bytes, os.PathLike)):
        chans, summary = read_exr(reference)
        name = os.fsdecode(reference)
        if not all(c in chans for c in "RGB"):
            raise ValueError(f"reference: {name} has no R, G, B channels")
        rgb = np.stack([chans[c] for c in "RGB"], -1)
    else:
        return image_from_array(reference, "reference"), None, "array", {}
    se = [chans.get(f"stderr.{c}") for c in "RGB"]
    noise = np.stack(se, -1) if all(x is not None for x in se) else None
    return image_from_array(rgb, "reference"), noise, name, summary if isinstance(summary, dict) else {}


def compare(render, reference):
    """The render's R, G, B against a reference (a Render, e.g. backend="mc"; an EXR path; or an
    array (h, w, 3 or 4)), as `icshadow render --compare` reports it: rmse, max_error, max_at
    [x, y], psnr_db; from the reference's summary (a Render's, or the one the CLI keeps in its
    EXR) reference_backend, reference_device, reference_spp and ms_reference; and where the
    reference carries its standard error (stderr AOVs) reference_noise and rmse_beyond_noise =
    sqrt(max(0, rmse^2 - noise^2))."""
    rgba = render.rgba if isinstance(render, Render) else render
    a = image_from_array(rgba, "render")
    b, noise, name, ref_summary = _reference(reference)
    if (a.width, a.height) != (b.width, b.height):
        raise ValueError(f"compare: the reference is {b.width}x{b.height}, the render "
                         f"{a.width}x{a.height}")
    d = ffi.new("ics_image_diff *")
    check(lib.ics_image_diff_rgb(a, b, d), context="compare: ")
    out = {"reference": name}
    for key, ref_key in (("reference_backend", "backend"), ("reference_device", "device"),
                         ("reference_spp", "spp"), ("ms_reference", "ms_render")):
        if ref_key in ref_summary:
            out[key] = ref_summary[ref_key]
    out.update({"rmse": d.rmse, "max_error": d.max_abs, "max_at": [d.max_x, d.max_y],
                "psnr_db": d.psnr})
    if noise is not None:
        n = float(np.sqrt(np.mean(np.square(noise, dtype=np.float64))))
        out["reference_noise"] = n
        out["rmse_beyond_noise"] = float(np.sqrt(max(0.0, d.rmse ** 2 - n ** 2)))
    return out


def backends():
    """Every backend built into the library: name, description, whether it can run here
    (available) and if not why, and its options (render's backend_options): name, help, the
    values it accepts (None: any) and the environment variable of its default."""
    def text(p):
        return ffi.string(p).decode() if p != ffi.NULL else None

    out = []
    for i in range(lib.ics_backend_count()):
        name = text(lib.ics_backend_name(i))
        why = msg_buffer()
        ok = lib.ics_backend_available(name.encode(), why, len(why))
        options = [{"name": f"{name}.{text(lib.ics_backend_option_name(i, j))}",
                    "help": text(lib.ics_backend_option_help(i, j)),
                    "values": text(lib.ics_backend_option_values(i, j)),
                    "env": text(lib.ics_backend_option_env(i, j))}
                   for j in range(lib.ics_backend_option_count(i))]
        out.append({"name": name, "description": text(lib.ics_backend_description(i)),
                    "available": bool(ok), "why": "" if ok else ffi.string(why).decode(),
                    "options": options})
    return out
