"""The command-line conventions every `harvest-stack` command shares with the C programs
(docs/EXIT_CODES.md): the exit codes, the one-line error `PROGRAM: what: why` on stderr, and
an argparse parser that reports its own errors so, ending each --help with the exit codes."""

import argparse
import re
import signal
import sys
import textwrap

EXIT_OK = 0  # done
EXIT_FAILURE = 1  # runtime failure: I/O, the bus, a program it runs
EXIT_USAGE = 2  # usage or bad input: nothing done, the option or file named

EXIT_CODES_HELP = "Exit codes: docs/EXIT_CODES.md (0 done, 1 runtime failure, 2 usage or bad input"


def exit_codes_help(*higher):
    """The last paragraph of a --help: the common codes, then `higher` ("3 ...") of the
    command, wrapped to 88 columns as the C programs' are."""
    return textwrap.fill(EXIT_CODES_HELP + "".join(", " + h for h in higher) + ")", width=88)


def error(program, what, why=None):
    """Print `PROGRAM: what: why` (or `PROGRAM: what`) on stderr."""
    print(f"{program}: {what}" + (f": {why}" if why else ""), file=sys.stderr)


def stop_on_signals():
    """SIGINT and SIGTERM ask a command that runs until stopped to finish cleanly, rather
    than kill it: returns a callable that is true once one of them came."""
    came = []

    def on_signal(signum, frame):
        came.append(signum)

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    return lambda: bool(came)


def open_lcm(program, option, url):
    """lcm.LCM(url), or None once `PROGRAM: OPTION URL: LCM could not be opened` is on stderr
    (LCM's own line before it says why)."""
    import lcm

    try:
        return lcm.LCM(url)
    except RuntimeError:
        error(program, f"{option} {url}", "LCM could not be opened")
        return None


def os_error(e):
    """An OSError as `FILE: reason` (Python's own text leaves the file to the end, quoted)."""
    if e.filename is None:
        return e.strerror or str(e)
    return f"{e.filename}: {e.strerror or e}"


class Parser(argparse.ArgumentParser):
    """argparse with the house's messages: `PROGRAM: --out: required (see --help)` and exit 2
    for every command-line error, `PROGRAM: --bogus: unknown option (see --help)` for an
    argument nothing takes; its help (and each sub-command's) ends with the exit codes,
    `exit_codes` naming the codes above 2 (add_parser passes it on)."""

    def __init__(self, *args, exit_codes=(), **kwargs):
        self.exit_codes = exit_codes
        super().__init__(*args, **kwargs)

    def format_help(self):
        """argparse's help, then the exit codes as a paragraph of their own (an epilog would
        be run together with the parser's own)."""
        return super().format_help() + "\n" + exit_codes_help(*self.exit_codes) + "\n"

    def error(self, message):
        m = re.match(r"argument (\S+): (.*)", message, re.S)
        if m:
            what, why = m.group(1), m.group(2)
            if why.startswith("expected ") and why.endswith(" argument"):
                why = "needs a value"
            self.fail(what, why)
        if message.startswith("the following arguments are required: "):
            self.fail(message.split(": ", 1)[1], "required")
        print(f"{self.prog}: {message} (see --help)", file=sys.stderr)
        sys.exit(EXIT_USAGE)

    def fail(self, what, why):
        """`PROGRAM: what: why (see --help)`, exit 2."""
        error(self.prog, what, f"{why} (see --help)")
        sys.exit(EXIT_USAGE)

    def parse_args(self, args=None, namespace=None):
        ns, extra = self.parse_known_args(args, namespace)
        if extra:
            first = extra[0]
            self.fail(first, "unknown option" if first.startswith("-") else "unexpected argument")
        return ns
