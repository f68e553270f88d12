"""What the commands of ``python -m mpisph`` parse alike: a parser whose errors are InputErrors (one
line, status 2), and ``--set NAME=VALUE`` items."""

import argparse
import sys

from .errors import InputError


class Parser(argparse.ArgumentParser):
    """Errors as InputErrors. ``--set`` takes every word up to the next option, so in ``--set dp=0.1
    CASE`` it takes the case too, and argparse would say only that the case is missing: the error
    then names the word."""

    def parse_args(self, args=None, namespace=None):
        self._words = list(sys.argv[1:] if args is None else args)
        return super().parse_args(args, namespace)

    def error(self, message):
        stray = next((word for word in set_words(getattr(self, "_words", [])) if "=" not in word), None)
        if stray is not None and "required" in message:
            message = f"--set took {stray!r}, which is no NAME=VALUE item: give the case before --set"
        raise InputError(message)


def set_words(words):
    """The words that follow ``--set`` in ``words``, up to the next option."""
    taken, out = False, []
    for word in words:
        if word.startswith("-"):
            taken = word == "--set"
        elif taken:
            out.append(word)
    return out


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
