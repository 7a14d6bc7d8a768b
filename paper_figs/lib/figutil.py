"""figutil.py — helpers shared by the paper_figs/*.py scripts (a module, not a figure script:
it lives in lib/ so that `make figs`, which runs every paper_figs/*.py, does not run it).

load_scene  a scene file of scenes/ (the figure's main configuration) as a dict, for the script
            to apply its sweep's overrides to;
arg_parser  the --cli/--out argument parser every script starts from (add options to it);
parse_args  parses them (a docstring or an arg_parser) and creates the --out folder;
run_cli     runs the icshadow CLI and returns its stdout, or exits naming the failed command;
write_csv   writes rows atomically (temporary file + rename), floats as %.17g;
write_text  writes a text file atomically;
save_fig    saves a matplotlib figure atomically.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

SCENES = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "scenes")


def load_scene(name):
    """The scene file scenes/NAME.json as a dict (a fresh copy on every call: the caller may change it)."""
    with open(os.path.join(SCENES, name + ".json")) as f:
        return json.load(f)


def arg_parser(doc):
    """ArgumentParser with the --cli and --out options of every figure script; doc is its help text."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default="build/bin/icshadow", help="path to the icshadow binary")
    ap.add_argument("--out", default="out/figs", help="output folder")
    return ap


def parse_args(doc_or_parser):
    """Parse the command line (a docstring: --cli and --out only; or a parser from arg_parser with
    more options added) and create the --out folder."""
    ap = arg_parser(doc_or_parser) if isinstance(doc_or_parser, str) else doc_or_parser
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    return args


def run_cli(cli, args, stdin_text=None):
    """stdout of `cli args...` (stdin_text, if given, fed to its stdin); exits with the command and
    its stderr when it fails."""
    args = list(args)
    res = subprocess.run([cli] + args, input=stdin_text, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit("icshadow %s failed (exit %d): %s" % (" ".join(args), res.returncode, res.stderr.strip()))
    return res.stdout


def _cell(v):
    return "%.17g" % v if isinstance(v, float) or type(v).__name__.startswith("float") else v


def write_csv(path, header, rows):
    """Write header + rows to path through a temporary file, so no partial CSV is left behind.
    Floats (Python or numpy) are written as %.17g, everything else as csv.writer writes it."""
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for row in rows:
            w.writerow([_cell(v) for v in row])
    os.replace(tmp, path)


def write_text(path, text):
    """Write text to path through a temporary file."""
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def save_fig(fig, path, dpi):
    """fig.savefig through a temporary file in the same folder, then rename."""
    root, ext = os.path.splitext(path)
    tmp = root + ".tmp" + ext
    fig.savefig(tmp, dpi=dpi)
    os.replace(tmp, path)
