#!/usr/bin/env python3
"""ss_man.py SUBSPECTRA VERSION OUT -- write the man page subspectra(1).

The page is made at build time from the program's own --help texts (the
overview, then every command's, and every sub-command's where a command has
them, as `enumerate` does), so it says exactly what --help says.  The texts
are kept as preformatted blocks: they are laid out for a terminal already, and
reflowing them would break their option tables.  help2man would do the same
but is not a build dependency.
"""
import re
import subprocess
import sys


def run_help(exe, args):
    """The --help text of `subspectra ARGS`; fails the build if it fails."""
    p = subprocess.run([exe] + args + ["--help"], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("ss_man.py: %s %s --help exited with %d: %s"
                 % (exe, " ".join(args), p.returncode, p.stderr.strip()))
    return p.stdout


def roff(text):
    """Text made safe for a roff no-fill block: backslashes and minus signs
    escaped, a leading '.' or "'" (a request) protected."""
    out = []
    for line in text.rstrip("\n").split("\n"):
        line = line.replace("\\", "\\e").replace("-", "\\-")
        if line.startswith((".", "'")):
            line = "\\&" + line
        out.append(line)
    return "\n".join(out)


def block(text):
    return ".nf\n" + roff(text) + "\n.fi\n"


def commands(text):
    """Names of the commands an overview lists: the indented 'NAME  summary'
    lines of the paragraph after its 'commands:' line, or, for a command with
    sub-commands, of the paragraph before its 'WHAT --help' line."""
    names = []
    for line in text.split("\n"):
        m = re.match(r"^  ([a-z][a-z0-9-]*) {2,}\S", line)
        if m:
            names.append(m.group(1))
    return names


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: ss_man.py SUBSPECTRA VERSION OUT")
    exe, version, out = sys.argv[1:]
    overview = run_help(exe, [])
    first = overview.split("\n", 1)[0]
    summary = first.split(" \u2014 ", 1)[1] if " \u2014 " in first else "subdivision schemes"
    page = [
        '.TH SUBSPECTRA 1 "" "subspectra %s" "User Commands"' % version,
        ".SH NAME",
        "subspectra \\- " + roff(summary),
        ".SH SYNOPSIS",
        ".B subspectra",
        ".I COMMAND",
        "[\\fIOPTIONS\\fR] ...",
        ".SH DESCRIPTION",
        block(overview.split("\n", 1)[1].lstrip("\n")).rstrip("\n"),
        ".SH COMMANDS",
    ]
    for cmd in commands(overview):
        text = run_help(exe, [cmd])
        page += [".SS " + cmd, block(text).rstrip("\n")]
        if "WHAT --help" in text:
            for sub in commands(text):
                page += [".SS %s %s" % (cmd, sub),
                         block(run_help(exe, [cmd, sub])).rstrip("\n")]
    page += [
        ".SH ENVIRONMENT",
        ".TP",
        ".B SUBSPECTRA_DATADIR",
        "the folder of the installed data (stencils/, reference/, meshes/);"
        " `reproduce' reads its reference values from its reference/ folder",
        ".SH SEE ALSO",
        "The README of the source distribution; the library: pkg\\-config subspectra.",
    ]
    with open(out, "w", encoding="utf-8") as f:
        f.write("\n".join(page) + "\n")


if __name__ == "__main__":
    main()
