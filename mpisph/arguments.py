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
    """{name: text} of ``--set`` items."""
    out = {}
    for item in items:
        if "=" not in item:
            raise InputError(f"--set takes NAME=VALUE, not {item!r}")
        name, value = item.split("=", 1)
        out[name.strip()] = value.strip()
    return out
