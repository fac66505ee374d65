"""gen_cdef.py OUTPUT HEADER... -- the cffi declarations of the Python package,
taken from the public headers at build time (python/meson.build), not copied
by hand: a field added to a structure the package reads reaches the package
with the next build.

The package names what it uses (NAMES below: types and functions); each is
looked up in the headers, whose text is read as C without a preprocessor:
comments dropped, `#define NAME INTEGER` kept (cffi takes those as constants,
array sizes among them), other preprocessor lines and SS_BEGIN_DECLS /
SS_END_DECLS dropped, static inline functions skipped.  A top-level statement
declares a name: `typedef ... NAME;`, a function pointer typedef
`typedef R (*NAME)(...);`, or a prototype `R NAME(...);`.  The headers are
ordered by their #include lines, the declarations by their headers and then
by their place in them, so a type comes before its users.  A name not found
is an error, and so is text cffi cannot parse (checked here when cffi is
installed).  Writes OUTPUT: a module with CDEF, the declarations' text.
"""
import os
import re
import sys

# What subspectra/__init__.py uses, types before functions.
NAMES = [
    # ss_error.h, ss_progress.h, ss_cx.h, ss_link.h, ss_star.h
    "ss_status", "ss_error", "ss_progress_fn", "ss_progress", "ss_cell_type", "ss_idx", "ss_cx",
    "ss_link", "ss_star_coord", "ss_diag_mode",
    # ss_scheme.h, ss_case.h
    "ss_scheme", "ss_case_kind", "ss_case",
    # ss_local.h, ss_eig.h, ss_eigvec.h, ss_report_case.h
    "ss_verdict_kind", "ss_judged_on", "ss_verdict", "ss_local_ring", "ss_local", "ss_eigval", "ss_eig", "ss_eig_opts", "ss_eigvec",
    "ss_report_analyze_opts",
    # ss_enum.h, ss_jsr.h, ss_levin.h
    "ss_enum_opts", "ss_enum_visit", "ss_jsr_norm", "ss_jsr_opts", "ss_jsr_result",
    "ss_levin",
    # ss_limit.h (limit); ss_result.h, ss_store.h, ss_report_table.h (store)
    "ss_limit", "ss_limit_point", "ss_verdicts", "ss_result_eigval", "ss_result_psi",
    "ss_result", "ss_store", "ss_store_mode", "ss_report_row", "ss_report_rows",
    "ss_report_summary", "ss_report_format",
    # ss_mesh.h (read_mesh, write_mesh)
    "ss_mesh_format", "ss_mesh_fields", "ss_mesh_write_opts",
    # functions
    "ss_scheme_names", "ss_scheme_new", "ss_scheme_free",
    "ss_link_parse", "ss_link_free", "ss_link_format", "ss_diag_parse",
    "ss_local_new", "ss_local_free",
    "ss_eig_defaults", "ss_eig_new", "ss_eig_free",
    "ss_eigvec_new", "ss_eigvec_free",
    "ss_report_analyze_defaults", "ss_report_analyze",
    "ss_enum_links",
    "ss_jsr_defaults", "ss_jsr_compute", "ss_jsr_result_clear",
    "ss_levin_new", "ss_levin_verdict", "ss_levin_free",
    "ss_cx_new", "ss_cx_free", "ss_cx_reserve_vertices", "ss_cx_reserve_cells",
    "ss_cx_validate", "ss_cx_check_orientation", "ss_cell_nverts",
    "ss_scheme_refine_levels", "ss_scheme_reads_diagonals", "ss_diag_choose",
    "ss_case_name", "ss_diag_name", "ss_verdict_name",
    "ss_limit_new_fields", "ss_limit_free", "ss_limit_ncells", "ss_limit_nfields",
    "ss_limit_eval_fields", "ss_limit_eval_reference_fields",
    "ss_store_open", "ss_store_close", "ss_report_rows_load", "ss_report_rows_clear",
    "ss_report_table_write",
    "ss_mesh_format_from_name", "ss_mesh_read_fields", "ss_mesh_write",
]


def strip(text):
    """Comments out, continuation lines joined."""
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    return text.replace("\\\n", " ")


def statements(text):
    """(kind, name, text) of the header's top-level declarations; kind
    'define' for integer #defines."""
    out = []
    body = []
    for line in text.split("\n"):
        m = re.match(r"\s*#\s*define\s+(\w+)\s+(-?(?:0x[0-9a-fA-F]+|\d+))\s*$", line)
        if m:
            out.append(("define", m.group(1), "#define %s %s" % (m.group(1), m.group(2))))
        elif not line.lstrip().startswith("#"):
            body.append(line)
    text = re.sub(r"\bSS_(BEGIN|END)_DECLS\b", " ", "\n".join(body))
    depth, start = 0, 0
    for i, ch in enumerate(text):
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
            if depth == 0 and re.match(r"\s*static\b", text[start:i]):
                start = i + 1  # an inline function's body: skipped
        elif ch == ";" and depth == 0:
            stmt = " ".join(text[start:i + 1].split())
            start = i + 1
            if stmt.startswith("static "):
                continue
            m = re.match(r"typedef\b[^(]*\(\s*\*\s*(\w+)\s*\)", stmt)
            if m:
                out.append(("decl", m.group(1), stmt))
            elif stmt.startswith("typedef"):
                m = re.search(r"(\w+)\s*(?:\[[^\]]*\]\s*)*;$", stmt)
                out.append(("decl", m.group(1), stmt))
            elif "(" in stmt:
                m = re.search(r"(\w+)\s*\(", stmt)
                out.append(("decl", m.group(1), stmt))
    return out


def ordered(paths):
    """The headers, each after the ones it includes (among these)."""
    by_name = {os.path.basename(p): p for p in paths}
    done, order = set(), []

    def visit(p):
        if p in done:
            return
        done.add(p)
        with open(p) as f:
            for inc in re.findall(r'#\s*include\s+"([^"]+)"', f.read()):
                if inc in by_name:
                    visit(by_name[inc])
        order.append(p)
    for p in sorted(paths):
        visit(p)
    return order


def main(argv):
    out, headers = argv[1], argv[2:]
    found, defines = {}, []
    for rank, p in enumerate(ordered(headers)):
        with open(p) as f:
            for pos, (kind, name, text) in enumerate(statements(strip(f.read()))):
                if kind == "define":
                    defines.append(text)
                elif name in NAMES and name not in found:
                    found[name] = (rank, pos, text)
    missing = [n for n in NAMES if n not in found]
    if missing:
        sys.exit("gen_cdef: not declared in the headers given: " + ", ".join(missing))
    decls = [found[n][2] for n in sorted(found, key=lambda n: found[n][:2])]
    cdef = "\n".join(defines + decls) + "\n"
    try:
        from cffi import FFI
    except ImportError:
        pass
    else:
        FFI().cdef(cdef)  # what cffi cannot parse fails the build, not the import
    with open(out, "w") as f:
        f.write('"""Generated by python/gen_cdef.py from the public headers: the cffi\n'
                'declarations of the types and functions the package uses."""\n')
        f.write("CDEF = r'''\n%s'''\n" % cdef)


if __name__ == "__main__":
    main(sys.argv)
