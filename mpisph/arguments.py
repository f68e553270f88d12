"""What the commands of ``python -m mpisph`` parse alike: a parser whose errors are InputErrors (one
line, status 2), and ``--set NAME=VALUE`` items."""

import argparse
import sys

from .errors import InputError


COMPARE_USAGE = ("python -m mpisph compare CASE --stabiliser NAME,NAME,...|--vary NAME=A,B,... [--set NAME=VALUE ...] "
                 "[--t-end T] [--output-interval DT] [-n RANKS] [--out DIR] [--colour FIELD]")  # compare.py


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


def add_times(parser):
    """``--t-end`` and ``--output-interval``, the --set items t_end and output_interval by another name."""
    parser.add_argument("--t-end", type=float, help="simulated end time [s]")
    parser.add_argument("--output-interval", type=float, help="simulated time between frames [s]")


def with_times(sets, args):
    """The --set items ``sets`` ({name: text}) with the times of ``add_times`` in ``args``; a time
    given both ways with two values is refused."""
    out = dict(sets)
    for name, option, value in (("t_end", "--t-end", args.t_end), ("output_interval", "--output-interval",
                                                                  args.output_interval)):
        if value is None:
            continue
        if name in out and not _same_number(out[name], value):
            raise InputError(f"{option} {value:g} and --set {name}={out[name]} disagree: keep one")
        out[name] = repr(value)
    return out


def _same_number(text, value):
    """Whether the --set ``text`` is the number ``value`` (text that is no number is not)."""
    try:
        return float(text) == value
    except ValueError:
        return False


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
