"""What the commands of ``python -m mpisph`` parse alike: a parser whose errors are InputErrors (one
line, status 2), and ``--set NAME=VALUE`` items."""

import argparse

from .errors import InputError


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise InputError(message)


def add_set(parser):
    """The repeatable ``--set NAME=VALUE ...`` option, into ``overrides``."""
    parser.add_argument("--set", dest="overrides", nargs="+", action="extend", default=[],
                        metavar="NAME=VALUE", help="override a case parameter")


def parse_sets(items):
    """{name: text} of ``--set`` items; a name given twice with different values is refused rather
    than one of them silently dropped."""
    out = {}
    for item in items:
        if "=" not in item:
            raise InputError(f"--set takes NAME=VALUE, not {item!r}")
        name, value = (part.strip() for part in item.split("=", 1))
        if out.get(name, value) != value:
            raise InputError(f"--set gives {name} twice, {out[name]!r} and {value!r}: keep one")
        out[name] = value
    return out
