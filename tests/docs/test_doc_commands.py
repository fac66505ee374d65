#!/usr/bin/env python3
"""test_doc_commands.py EXE SRCDIR [PAGE...] -- the commands the README and
docs/*.md show, run, and their output compared with what the page shows.

A shown command is a line "$ COMMAND" in an indented code block; the lines
after it, up to the next "$ " line or the end of the block, are its output
(standard output and standard error: the shown lines must be an interleaving
of the two, each in its order, as a terminal may show them).  COMMAND runs with
bash in a fresh directory per page (the page's commands in order, so that a
store written by one is read by the next), with data/ and tests/ of SRCDIR
beside it; "./run" and a leading "subspectra" stand for EXE.

Compared after masking what a machine changes: times ("0.000 s", "(3s",
"seconds":...), rates ("443749 links/s", "30.3 cases/s"), ETAs.  In the shown
output "…" or "..." stands for anything: a line of its own for any number of
lines (none included), inside a line for any text.  The exit status must be 0 unless the page says
otherwise (pages show failures on purpose), on the line before the block:
    <!-- doc-test: exit N [N ...] -->
one status per command of the block in order, or one for all.

A block without "$ " lines that shows commands without their output (a
line "./run COMMAND ...", "subspectra COMMAND ...", "python3 data/...",
"mpirun ...", or a shell "for" loop; a line "subspectra COMMAND: ..." is a
message, not a command) is run whole as one bash script: its output is not
compared, its exit status is (0 unless an "exit" line says otherwise; with
set -e, so the status is the first failing command's).
Any other block without "$ " lines is a listing.

A page says when a block is not run, on the line before it:
    <!-- doc-test: skip REASON -->
(the build script itself, a Slurm batch script, minutes of computing, a
terminal), masks more in the next block:
    <!-- doc-test: mask REGEX -->
runs it with a placeholder of the page replaced (a user's file):
    <!-- doc-test: replace TEXT WITH -->
or runs it and compares only the exit status (output made for a terminal):
    <!-- doc-test: run-only REASON -->
A block of Python (its first line "import ..." or "from ...") runs with
python3 and the package of this build (SS_DOC_PYBUILD: the build's python/
folder with _cdef.py and _config.py, the package's sources taken from
SRCDIR/python; SS_DOC_LIBRARY: the shared library; SS_DOC_PYTHON: the
interpreter, python3 by default), its exit status
compared; without SS_DOC_PYBUILD it is skipped, saying so.
A "$ mpirun ..." command runs when mpirun is installed (as root with
OMPI_ALLOW_RUN_AS_ROOT), else it is skipped, saying so; commands of other
programs (python3, sbatch, srun) in "$ " lines are not run.

Each page is a line of the output: commands run and matched, skipped (with
the reasons).  Exit 1 if a command's output does not match, or if no command
ran at all (the parser would have found nothing).  First a self-test on a
small page: a matching command passes, so does one with lines left out as an
ellipsis; a wrong shown line, a line left out without one and an extra line fail.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

TIMEOUT = 120  # seconds per command: a page's command beyond that is a bug

MASKS = [
    (re.compile(r'"seconds":\s*[-+0-9.eE]+'), '"seconds":<T>'),
    (re.compile(r'\b\d+(\.\d+)?(e[-+]?\d+)? ?(s|ms|µs)\b(?!/)'), '<T> s'),
    (re.compile(r'\b\d+(\.\d+)? ([a-z]+)/s\b'), r'<R> \2/s'),
    (re.compile(r'\bETA [^;,) ]+'), 'ETA <T>'),
]
ELLIPSIS = re.compile(r'…|\.\.\.')


def mask(line, extra):
    for rx, rep in MASKS:
        line = rx.sub(rep, line)
    for rx in extra:
        line = rx.sub('<M>', line)
    return line.rstrip()


def blocks(text):
    """Yield (first line number, directives, lines) of the indented code
    blocks of a Markdown page; directives are those of the comment lines
    just before the block."""
    lines = text.split('\n')
    i, n = 0, len(lines)
    pending = []
    fence = False
    while i < n:
        s = lines[i]
        if s.lstrip().startswith('```'):
            fence = not fence
            i += 1
            continue
        m = re.match(r'\s*<!-- doc-test: (skip|mask|exit|replace|run-only) (.*?) -->\s*$', s)
        if m:
            pending.append((m.group(1), m.group(2)))
            i += 1
            continue
        if not fence and s.startswith('    ') and (i == 0 or lines[i - 1].strip() == ''):
            start = i
            body = []
            while i < n and (lines[i].startswith('    ') or lines[i].strip() == ''):
                body.append(lines[i][4:])
                i += 1
            while body and body[-1].strip() == '':
                body.pop()
            yield start + 1, pending, body
            pending = []
            continue
        if s.strip() and not s.startswith('<!--'):
            pending = [] if not s.startswith('    ') else pending
        i += 1


# a line of a block that is a command shown without its output
SCRIPT_LINE = re.compile(r'((\./run|subspectra) [a-z][-a-z0-9]*(\s|$)|python3 data/|mpirun |'
                         r'for \w+ in .*; do$|srun |sbatch |meson |ninja |cc )')


class Command:
    """A command of a page: line, text, shown output (None: a script block,
    output not compared), skip reason or None, extra masks, expected exit
    status."""

    def __init__(self, line, cmd, shown, skip, extra, status):
        self.line, self.cmd, self.shown = line, cmd, shown
        self.skip, self.extra, self.status = skip, extra, status


def commands(text):
    """Yield a Command for every "$ " command of a page, and one for every
    block of commands shown without output."""
    for start, directives, body in blocks(text):
        skip = next((a for k, a in directives if k == 'skip'), None)
        extra = [re.compile(a) for k, a in directives if k == 'mask']
        status = next((list(map(int, a.split())) for k, a in directives if k == 'exit'), [0])
        for k, a in directives:
            if k == 'replace':
                old, new = a.split(None, 1)
                body = [s.replace(old, new) for s in body]
        found = []
        run_only = any(k == 'run-only' for k, a in directives)
        for j, s in enumerate(body):
            if s.startswith('$ '):
                found.append(Command(start + j, s[2:], None if run_only else [], skip, extra, 0))
            elif found and found[-1].shown is not None:
                found[-1].shown.append(s)
        if found and body[0].strip() and not body[0].startswith('$ ') and not run_only:
            # output shown before any command: a command line lost from the page
            yield Command(start, None, body[:1], skip, extra, 0)
        if not found and re.match(r'(import|from) \w', body[0] if body else ''):
            found = [Command(start, 'python3\n' + '\n'.join(body), None, skip, extra, 0)]
        elif not found and any(SCRIPT_LINE.match(s.strip()) for s in body):
            found = [Command(start, '\n'.join(body), None, skip, extra, 0)]
        for i, c in enumerate(found):
            c.status = status[i] if i < len(status) else status[-1]
            yield c


def program_command(cmd):
    """The command with EXE for ./run and subspectra, or None when it runs
    another program; in "mpirun ... subspectra ..." EXE runs under mpirun."""
    first = re.split(r'\s*\|\s*', cmd)
    if not any(re.match(r'(mpirun .*?)?(\./run|subspectra)\b', p) for p in first):
        return None
    if re.match(r'(sbatch|srun|python3|/usr/bin/time)\b', cmd):
        return None
    if cmd.startswith('mpirun '):
        return re.sub(r'\s(\./run|subspectra)\b', ' "$SS"', cmd, count=1)
    return re.sub(r'(^|\|\s*)(\./run|subspectra)\b', r'\1"$SS"', cmd)


def python_package(src, work):
    """The Python package of this build under work/py (the sources from
    SRCDIR/python, _cdef.py and _config.py from SS_DOC_PYBUILD), or None when
    SS_DOC_PYBUILD is not set."""
    build = os.environ.get('SS_DOC_PYBUILD')
    if not build:
        return None
    pkg = os.path.join(work, 'py', 'subspectra')
    os.makedirs(pkg)
    for d in (os.path.join(src, 'python', 'subspectra'), build):
        for f in os.listdir(d):
            if f.endswith('.py'):
                os.symlink(os.path.join(d, f), os.path.join(pkg, f))
    return os.path.dirname(pkg)


def run_only_cmd(c):
    """Whether c is a "$ " command of a run-only block (one line, no
    shown output to compare): run as a command, not as a script."""
    return c.shown is None and '\n' not in c.cmd and not c.cmd.startswith('python3')


def script_command(block):
    """A block of commands shown without output as one bash script (set -e:
    its status is the first failing command's): EXE for ./run and
    subspectra where a line starts with them; the rest as shown."""
    return 'set -e\n' + '\n'.join(re.sub(r'^(\s*)(\./run|subspectra)\b', r'\1"$SS"', s)
                     for s in block.split('\n'))


def matches(shown, out, err):
    """Whether the shown lines (masked, with ellipses) are an interleaving of
    the standard output and standard error lines, each in its order (a page
    shows them as a terminal does; a pipe buffers them differently)."""
    pats = []
    for s in shown:
        if ELLIPSIS.fullmatch(s.strip()):
            pats.append(None)
        else:
            parts = ELLIPSIS.split(s)
            pats.append(re.compile('.*'.join(re.escape(p) for p in parts) + r'\s*'))
    memo = {}

    def go(i, a, b):
        key = (i, a, b)
        if key in memo:
            return memo[key]
        memo[key] = False
        if i == len(pats):
            r = a == len(out) and b == len(err)
        elif pats[i] is None:
            r = (go(i + 1, a, b) or (a < len(out) and go(i, a + 1, b)) or
                 (b < len(err) and go(i, a, b + 1)))
        else:
            r = ((a < len(out) and pats[i].fullmatch(out[a]) is not None and go(i + 1, a + 1, b)) or
                 (b < len(err) and pats[i].fullmatch(err[b]) is not None and go(i + 1, a, b + 1)))
        memo[key] = r
        return r

    sys.setrecursionlimit(100000)
    return go(0, 0, 0)


def lines_of(data, extra):
    got = data.decode('utf-8', 'replace').split('\n')
    while got and got[-1] == '':
        got.pop()
    return [mask(g, extra) for g in got]


def run_page(exe, src, path, text, out):
    """Run a page's commands; return (ran, skipped reasons, failures)."""
    ran, skipped, failures = 0, [], []
    work = tempfile.mkdtemp(prefix='doccmd.')
    try:
        for d in ('data', 'tests'):
            os.symlink(os.path.join(src, d), os.path.join(work, d))
        env = dict(os.environ, SS=exe, LC_ALL='C.UTF-8', OMPI_ALLOW_RUN_AS_ROOT='1',
                   OMPI_ALLOW_RUN_AS_ROOT_CONFIRM='1')
        if env.get('LSAN_OPTIONS'):  # under the sanitizers: no statistics on stderr
            env['LSAN_OPTIONS'] += ':print_suppressions=0'
        py = python_package(src, work)
        if py:
            env.update(PYTHONPATH=py, SUBSPECTRA_LIBRARY=os.environ.get('SS_DOC_LIBRARY', ''),
                       SS_DOC_PYTHON=os.environ.get('SS_DOC_PYTHON', 'python3'))
        for c in commands(text):
            line, cmd, shown, extra = c.line, c.cmd, c.shown, c.extra
            if cmd is not None and cmd.startswith('python3\n'):
                if c.skip is not None or not py:
                    skipped.append(c.skip or 'Python: the package is not built (SS_DOC_PYBUILD)')
                    continue
                cmd = c.cmd = "python3 - <<'DOC_PYTHON_EOF'\n" + cmd[8:] + '\nDOC_PYTHON_EOF'
                shown = None
            if cmd is None:
                failures.append(f'{path}:{line}: output shown before any "$ " command: '
                                f'{shown[0]}')
                continue
            pc = (program_command(cmd) if shown is not None or run_only_cmd(c)
                  else script_command(cmd))
            if cmd.startswith('python3 - <<'):  # the interpreter the package was built for
                pc = '"$SS_DOC_PYTHON"' + cmd[7:]
            if c.skip is not None:
                skipped.append(c.skip)
                continue
            if pc is None:
                skipped.append('not subspectra: ' + cmd.split()[0])
                continue
            if cmd.startswith('mpirun ') and not shutil.which('mpirun'):
                skipped.append('mpirun is not installed')
                continue
            try:
                p = subprocess.run(['bash', '-c', pc], cwd=work, env=env,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                   timeout=TIMEOUT)
            except subprocess.TimeoutExpired:
                failures.append(f'{path}:{line}: {cmd}: still running after {TIMEOUT} s')
                continue
            ran += 1
            out, err = lines_of(p.stdout, extra), lines_of(p.stderr, extra)
            if p.returncode != c.status:
                failures.append(f'{path}:{line}: {cmd}\n  exit status {p.returncode}, the page '
                                f'says {c.status}:\n' +
                                ''.join(f'    {g}\n' for g in (err or out)[-20:]))
                continue
            if shown is None:
                continue
            want = [mask(s, extra) for s in shown]
            if not matches(want, out, err):
                failures.append(f'{path}:{line}: {cmd}\n  shown:\n' +
                                ''.join(f'    {s}\n' for s in want) + '  got (stdout):\n' +
                                ''.join(f'    {g}\n' for g in out[:60]) + '  got (stderr):\n' +
                                ''.join(f'    {g}\n' for g in err[:20]))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return ran, skipped, failures


def self_test(exe, src):
    """A page whose command lists the numbers of sphere triangulations with
    4..6 vertices (1, 1, 2): shown right it passes, with a wrong count or a
    line left out it fails, with the left-out lines as an ellipsis it passes."""
    cmd = "    $ ./run enumerate links --vertices 4..6 --count 2>/dev/null | tail -n 3\n"
    skip = '\n<!-- doc-test: skip a reason -->\n\n    $ ./run nothing\n    x\n'
    good = '# T\n\n' + cmd + '    4\t1\n    5\t1\n    6\t2\n' + skip
    cases = (('good', good, False),
             ('wrong line', good.replace('6\t2', '6\t3'), True),
             ('missing line', good.replace('    5\t1\n', ''), True),
             ('ellipsis', good.replace('    5\t1\n    6\t2\n', '    …\n'), False),
             ('extra line', good.replace('6\t2\n', '6\t2\n    7\t5\n'), True),
             ('output before the command', good.replace(cmd, '    4\t1\n' + cmd), True),
             ('exit status', good.replace('# T\n', '# T\n<!-- doc-test: exit 1 -->\n'), True))
    ok = True
    for name, text, want_fail in cases:
        ran, skipped, failures = run_page(exe, src, 'self-test', text, sys.stdout)
        if ran != 1 or skipped != ['a reason'] or bool(failures) != want_fail:
            print(f'self-test {name}: ran {ran}, skipped {skipped}, failures {failures}')
            ok = False
    return ok


def main():
    if len(sys.argv) < 3:
        print(__doc__.split('\n')[0])
        return 2
    exe, src = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    if not self_test(exe, src):
        print('doc commands: the self-test failed')
        return 1
    pages = sys.argv[3:] or (['README.md'] + sorted(
        'docs/' + f for f in os.listdir(os.path.join(src, 'docs')) if f.endswith('.md')))
    total, failed = 0, []
    for page in pages:
        with open(os.path.join(src, page), encoding='utf-8') as f:
            text = f.read()
        ran, skipped, failures = run_page(exe, src, page, text, sys.stdout)
        total += ran
        failed += failures
        why = '; '.join(sorted(set(skipped)))
        print(f'{page}: {ran} run, {ran - len(failures)} match'
              + (f', {len(skipped)} not run ({why})' if skipped else ''))
    for f in failed:
        print('MISMATCH ' + f)
    if total == 0:
        print('doc commands: no command found')
        return 1
    print(f'doc commands: {total} run, {len(failed)} do not match')
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
