"""`harvest-stack scenario`: write one fruit map (the planner's CSV) from a seed."""

import os

from ..cmdline import EXIT_FAILURE, EXIT_USAGE, Parser, error, os_error
from . import fruit_map, generate
from .config import Config, ConfigError, Row, default_config_path, derived_config_text

LONG_ROW_DEFAULT_M = 30.0
PROG = "harvest-stack scenario"


def build_parser():
    p = Parser(
        prog=PROG,
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
        error(PROG, str(e))
        return EXIT_USAGE
    length = args.length
    if length is None:
        length = LONG_ROW_DEFAULT_M if args.distribution == "long" else row.length_m
    if length <= 0:
        error(PROG, "--length", f"must be > 0, got {length:g}")
        return EXIT_USAGE
    n_left = args.left
    if n_left is None:
        n_left = generate.long_row_left_count(row, length)
    bad = (
        ("--left", f"must be >= 0, got {n_left}", n_left < 0),
        ("--alpha", f"must be >= 0, got {args.alpha:g}", args.alpha < 0),
        ("--gradient", f"must be in [-1, 1], got {args.gradient:g}", not -1 <= args.gradient <= 1),
        (
            "--config-out",
            f"needed: a {length:g} m row does not fit {args.config} (row.length = "
            f"{row.length_m:g}); it writes a config for it",
            abs(length - row.length_m) > 1e-9 and not args.config_out,
        ),
    )
    for what, why, wrong in bad:
        if wrong:
            error(PROG, what, why)
            return EXIT_USAGE
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
    except OSError as e:
        error(PROG, os_error(e))
        return EXIT_FAILURE
    except ConfigError as e:  # the config copied for --config-out
        error(PROG, str(e))
        return EXIT_USAGE
    except fruit_map.FruitMapError as e:  # an id the generator made outside the id set
        error(PROG, str(e))
        return EXIT_FAILURE
    n_right = sum(1 for f in fruits if f.side == "R")
    print(
        f"scenario: {args.distribution}, {len(fruits) - n_right} left + {n_right} right fruits "
        f"over {length:g} m -> {os.path.abspath(args.out)}"
    )
    return 0
