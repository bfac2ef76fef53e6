"""`hexapod sim [KIND]`: the simulations. Each kind lives in its own module with register(sub);
`hexapod sim` alone runs DEFAULT, the main job (what `make sim` runs)."""

import importlib

# Modules that add `hexapod sim KIND`; each defines register(subparsers).
SIM_MODULES = (
    "hexapod_host.commands.sim_kinematics",
    "hexapod_host.commands.sim_wall",
    "hexapod_host.commands.sim_physics",
)
DEFAULT = "wall"


def register(sub):
    p = sub.add_parser("sim", help="simulations; alone, the main job (%s)" % DEFAULT)
    kinds = p.add_subparsers(dest="sim_kind", metavar="KIND")
    for name in SIM_MODULES:
        importlib.import_module(name).register(kinds)
    p.set_defaults(func=lambda args: _default(kinds))


def _default(kinds):
    """No KIND given: DEFAULT with its default options."""
    args = kinds.choices[DEFAULT].parse_args([])
    return args.func(args)
