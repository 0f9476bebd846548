"""`python -m harvest scenario`: write one fruit map (the planner's CSV) from a seed."""

import argparse
import os
import sys

from . import fruit_map, generate
from .config import Config, ConfigError, Row, default_config_path, derived_config_text

LONG_ROW_DEFAULT_M = 30.0


def build_parser():
    p = argparse.ArgumentParser(
        prog="python -m harvest scenario",
        description="Generate a fruit map (CSV id,side,x,y,z,yaw; m, rad) inside the "
        "fruit-planted area of the config. Same arguments, same file.",
        epilog="distributions: uniform = the paper's (uniform position and yaw, m^L left, "
        "alpha*m^L right); clustered = trusses of ~4 fruits; gradient = ripe-fruit "
        "density rising linearly along the row; long = uniform over a long row "
        f"(default {LONG_ROW_DEFAULT_M:g} m at the paper's density).",
    )
    p.add_argument(
        "--config", default=default_config_path(), help="harvest config (default: %(default)s)"
    )
    p.add_argument("--distribution", choices=generate.DISTRIBUTIONS, default="uniform")
    p.add_argument(
        "--left",
        type=int,
        default=None,
        help=f"fruits on the left row, m^L (default {generate.PAPER_LEFT_FRUITS}, "
        "scaled by length for 'long')",
    )
    p.add_argument(
        "--alpha",
        type=float,
        default=1.0,
        help="right/left fruit ratio: the right row gets round(alpha*m^L) (default 1)",
    )
    p.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    p.add_argument(
        "--length",
        type=float,
        default=None,
        help="row length in m (default: row.length of the config; "
        f"{LONG_ROW_DEFAULT_M:g} for 'long')",
    )
    p.add_argument(
        "--gradient",
        type=float,
        default=0.8,
        help="'gradient' only: density goes from 1-G to 1+G along the row (default 0.8)",
    )
    p.add_argument("--out", required=True, help="fruit map CSV to write")
    p.add_argument(
        "--config-out",
        default=None,
        help="write a copy of the config with row.length set to --length "
        "(required when the row length differs from the config's)",
    )
    return p


def main(argv):
    args = build_parser().parse_args(argv)
    try:
        row = Row(Config.load(args.config))
    except ConfigError as e:
        print(f"scenario: {e}", file=sys.stderr)
        return 2
    length = args.length
    if length is None:
        length = LONG_ROW_DEFAULT_M if args.distribution == "long" else row.length_m
    if length <= 0:
        print(f"scenario: --length must be > 0, got {length}", file=sys.stderr)
        return 2
    n_left = args.left
    if n_left is None:
        n_left = generate.long_row_left_count(row, length)
    if n_left < 0 or args.alpha < 0:
        print("scenario: --left and --alpha must be >= 0", file=sys.stderr)
        return 2
    if not -1.0 <= args.gradient <= 1.0:
        print(f"scenario: --gradient must be in [-1, 1], got {args.gradient}", file=sys.stderr)
        return 2
    if abs(length - row.length_m) > 1e-9 and not args.config_out:
        print(
            f"scenario: a {length:g} m row does not fit {args.config} (row.length = "
            f"{row.length_m:g}): give --config-out PATH to write a config for it",
            file=sys.stderr,
        )
        return 2
    fruits = generate.generate(
        args.distribution,
        row,
        n_left,
        args.alpha,
        args.seed,
        length_m=length,
        gradient_g=args.gradient,
    )
    try:
        fruit_map.write(args.out, fruits)
        if args.config_out:
            text = derived_config_text(args.config, {"row.length": f"{length:g}"})
            with open(args.config_out, "w", encoding="utf-8") as f:
                f.write(text)
    except (OSError, ConfigError) as e:
        print(f"scenario: cannot write: {e}", file=sys.stderr)
        return 1
    n_right = sum(1 for f in fruits if f.side == "R")
    print(
        f"scenario: {args.distribution}, {len(fruits) - n_right} left + {n_right} right fruits "
        f"over {length:g} m -> {os.path.abspath(args.out)}"
    )
    return 0
