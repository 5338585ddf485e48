"""Command line of the generator (`python -m generator`, or `nmeaspec-gen` once installed):
validate the spec (with a receiver's own overlays), generate every output (or a renamed subset),
check it is fresh, print the API changelog between two spec trees, reconcile a manual's example
sentences with the spec, start an overlay's files, and list the spec's rules."""

from __future__ import annotations

import argparse
import sys
import textwrap
from pathlib import Path

from .errors import SpecErrors
from .paths import CHECKOUT, ROOT, VERSION

PROG = "nmeaspec-gen"

EPILOG = f"""\
examples:
  {PROG} validate                      check spec/ (every error at once: file:line: YAML path)
  {PROG} generate                      rewrite the files of generated/ whose content changed
  {PROG} check                         exit 1 when generated/ is stale
  {PROG} diff HEAD spec                changelog from the committed spec to the working tree
  {PROG} reconcile ../shared/seeds/000_6b9167a029107846.txt
  {PROG} generate --only standard,geos5 --prefix gs5 --namespace gs5nmea --out vendor/nmea
  {PROG} new sentence PACMEPOS --manual acme --spec-extra my-nmea
  {PROG} generate --spec-extra my-nmea --only standard,acme --prefix acme --out third_party/nmea
  {PROG} rules                         what each rule id of an error checks, and how to fix it

`python -m generator` is the same program, run from the checkout. It keeps the spec files it
parsed and validated for its next run, found by their text, in $NMEASPEC_GEN_CACHE (default
~/.cache/nmeaspec-gen; `off`: no cache).
"""


def _formatter(prog: str) -> argparse.HelpFormatter:
    return argparse.RawDescriptionHelpFormatter(prog, max_help_position=32)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog=PROG, formatter_class=_formatter, epilog=EPILOG,
        description="NMEA 0183 spec -> C, Python and Rust codecs, Markdown docs and test vectors.")
    parser.add_argument("--version", action="version", version=f"{PROG} {VERSION}")
    parser.add_argument("--spec", type=Path, default=ROOT / "spec", help="spec directory (default: %(default)s)")
    verbs = parser.add_subparsers(dest="verb", required=True, metavar="VERB")
    overlay = argparse.ArgumentParser(add_help=False)
    overlay.add_argument("--spec-extra", metavar="DIR", type=Path, action="append", default=[],
                         help="an overlay laid over the spec: its own manuals.yaml, enums/, proprietary/, extensions/ "
                              "... (repeatable)")

    def verb(name: str, help: str, description: str, examples: str) -> argparse.ArgumentParser:
        text = "\n\n".join(textwrap.fill(p, 100) for p in description.split("\n\n"))
        return verbs.add_parser(name, help=help, description=text, formatter_class=_formatter,
                                epilog="examples:\n" + examples, parents=[overlay] if name not in ("diff", "rules") else [])

    verb("validate", "check the spec against the schema and the semantic rules",
         "Load spec/, check every file against the JSON Schema, then the semantic rules (references, "
         "layouts, every manual example decodes to its expected values).\n\nEvery error is printed at "
         "once as FILE:LINE: YAML.PATH: message [RULE].",
         f"  {PROG} validate\n  {PROG} --spec /tmp/myspec validate\n  {PROG} validate --spec-extra my-nmea\n")

    out_help = "output directory (default: generated/ of the checkout; required outside a checkout)"
    gen = verb("generate", "write every generated file whose content changed",
               "Render every output and rewrite only the files whose content changed; print each "
               "created, updated or removed file and a summary line.\n\n"
               "Subsets: --only takes a comma-separated list of `standard`, vendor manual ids of "
               "spec/manuals.yaml (geos5, teseo, gs501, globalsat, comnav), sentence or command ids "
               "(GGA, GEOS5_JAMDET), proprietary addresses (GPSGG, PSTMSETPAR) and binary messages "
               "and protocols (NAV-PVT, ubx:NAV-PVT, sbf:pvt_geodetic, rtcm3:1005, sirf: once one is named, "
               "only the binary messages named are kept, with their replies such as ACK-ACK). Only "
               "the enums, bitfields and tables the subset uses come along; standard sentences keep the "
               "examples of every manual (they are their tests).\n\n"
               "Renaming: --prefix P renames the C API (nmea_* -> P_*, NMEA_* -> P_*, nmea.c/nmea.h -> "
               "P.c/P.h); --namespace N renames the Rust crate and the Python package (nmeaspec -> N) "
               "and its console scripts (nmea-py -> N-py). A subset or a renamed copy needs --out.\n\n"
               "Overlays: --spec-extra DIR lays a directory with the layout of spec/ (its own manuals.yaml, "
               "enums/, bitfields/, tables/, standard/, proprietary/, and extensions/ for variants, notes and "
               "examples of a sentence defined before it) over the spec; the same schema and rules apply to "
               "the whole, an id defined twice is an error naming both files, and --only selects from both.\n\n"
               "The output directory belongs to the generator: a file in it that the spec does not "
               "generate is removed (build products of cargo, pip and pytest excepted).",
               f"  {PROG} generate\n"
               f"  {PROG} generate --only standard,geos5 --out /tmp/nmea-geos5\n"
               f"  {PROG} generate --only standard,geos5 --prefix gs5 --namespace gs5nmea --out third_party/gs5\n"
               f"  {PROG} generate --only GGA,RMC,ubx:NAV-PVT,ubx:CFG-VALSET --out firmware/nmea\n")
    gen.add_argument("--out", type=Path, help=out_help)
    gen.add_argument("--only", metavar="SELECTOR",
                     help="emit a subset: standard, vendors, sentence ids, addresses, binary messages")
    gen.add_argument("--prefix", help="C symbol and file prefix instead of nmea")
    gen.add_argument("--namespace", help="Rust crate / Python package name instead of nmeaspec")
    gen.add_argument("-q", "--quiet", action="store_true", help="print only the summary line")

    chk = verb("check", "fail when the output differs from what the spec generates",
               "Exit 1 (listing the stale files) when the output directory differs from what the spec "
               "generates; takes the same options as generate.",
               f"  {PROG} check\n  {PROG} check --only standard,geos5 --prefix gs5 --out third_party/gs5\n")
    chk.add_argument("--out", type=Path, help=out_help)
    chk.add_argument("--only", metavar="SELECTOR")
    chk.add_argument("--prefix")
    chk.add_argument("--namespace")

    diff = verb("diff", "API changelog between two spec trees (directories or git revisions)",
                "Load OLD and NEW through the normal loader and model and print what changed for the "
                "users of the generated code: sentences and commands, fields (added, removed, renamed, "
                "retyped, reordered, optional, since), enum values, bitfields, tables and examples. Each "
                "change is tagged BREAKING (existing user code or existing wire data stops working) or "
                "compatible.\n\nOLD and NEW are each a spec directory (anything that exists on disk) or a "
                "git revision of the repository of the current directory: REV (its spec/), or REV:DIR.",
                f"  {PROG} diff HEAD spec                  the working tree against the last commit\n"
                f"  {PROG} diff HEAD~3 HEAD                two commits\n"
                f"  {PROG} diff main:spec /tmp/spec --json\n"
                f"  {PROG} diff v1.0 spec --fail-on-breaking   (CI: exit 1 on a breaking change)\n"
                f"  {PROG} diff --overlays HEAD:my-nmea my-nmea    your overlay's changes, over the built-in spec\n")
    diff.add_argument("old", metavar="OLD")
    diff.add_argument("new", metavar="NEW")
    diff.add_argument("--json", action="store_true", help="one JSON document instead of Markdown")
    diff.add_argument("--fail-on-breaking", action="store_true", help="exit 1 when a change is BREAKING")
    diff.add_argument("--overlays", action="store_true",
                      help="OLD and NEW are overlays (the layout of --spec-extra), each laid over the spec")

    rec = verb("reconcile", "compare a manual's example sentences with the spec",
               "Find every example sentence in a manual's text ($...*HH, and $... without a checksum, "
               "also when wrapped or typeset with spaces), check its checksum, and report for each "
               "whether it is already in the spec (as an example's raw or corrected text), whether it "
               "decodes with the spec (or the error), and unknown addresses; then the counts.",
               f"  {PROG} reconcile ../shared/seeds/000_6b9167a029107846.txt\n"
               f"  {PROG} reconcile new_manual.txt --manual geos5 --only-new\n")
    rec.add_argument("manual_text", metavar="MANUAL.txt", type=Path)
    rec.add_argument("--manual", metavar="ID", help="manual id of spec/manuals.yaml (default: guessed from the file name)")
    rec.add_argument("--only-new", action="store_true", help="list only the examples that are not in the spec")
    rec.add_argument("--json", action="store_true", help="JSON lines instead of text")

    new = verb("new", "start a manual, sentence or command of your own receiver in an overlay",
               "Write the starting YAML of a manual (an entry of the overlay's manuals.yaml), a proprietary "
               "sentence the receiver sends, or a command the host sends, into the overlay given by "
               "--spec-extra (the last one if several), or print it when none is given. A new sentence or "
               "command has one placeholder field and an example with a right checksum: it validates as "
               "written; replace the placeholders with what the manual says.",
               f"  {PROG} new manual acme --maker acme --title 'ACME X1 receiver, NMEA reference' --spec-extra my-nmea\n"
               f"  {PROG} new sentence PACMEPOS --manual acme --spec-extra my-nmea\n"
               f"  {PROG} new command PACMESET --manual acme --spec-extra my-nmea\n")
    new.add_argument("what", choices=("manual", "sentence", "command"))
    new.add_argument("id", metavar="ID", help="the manual's id (lower case) or the sentence's (upper case)")
    new.add_argument("--manual", metavar="M", help="sentence, command: the manual that documents it")
    new.add_argument("--address", help="sentence, command: the address after $ (default: the id)")
    new.add_argument("--maker", help="manual: who makes the receiver")
    new.add_argument("--title", help="manual: its title")

    rules = verb("rules", "list every rule id of the spec's errors: what it checks, how to fix it",
                 "Print the table of rules (generator/rules.py) whose ids end the errors of validate.",
                 f"  {PROG} rules\n  {PROG} rules --markdown > docs/rules.md\n")
    rules.add_argument("--markdown", action="store_true", help="the table as Markdown (docs/rules.md)")
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if args.verb == "rules":
        from . import rules
        print(rules.as_markdown() if args.markdown else rules.as_text(), end="")
        return 0
    if args.verb == "diff":
        from . import diff
        return diff.main(args)
    from .build import load_spec
    if args.verb == "new" and args.what == "manual":
        return _new_manual(args)
    try:
        spec = load_spec(args.spec, args.spec_extra)
    except SpecErrors as errs:
        print(errs, file=sys.stderr)
        print(f"{len(errs.errors)} error(s) in the spec", file=sys.stderr)
        return 1
    if args.verb == "validate":
        examples = sum(len(s.examples) for s in spec.sentences)
        print(f"spec ok: {len(spec.sentences)} sentences, {len(spec.enums)} enums, {examples} examples")
        return 0
    if args.verb == "reconcile":
        from . import reconcile
        return reconcile.main(spec, args)
    if args.verb == "new":
        return _new_sentence(spec, args)
    return _write(spec, args)


def _new_manual(args: argparse.Namespace) -> int:
    from .scaffold import MANUALS_HEADER, manual_entry
    if not (args.maker and args.title):
        print("new manual: give --maker and --title", file=sys.stderr)
        return 2
    entry = manual_entry(args.id, args.maker, args.title)
    if not args.spec_extra:
        print(MANUALS_HEADER + entry, end="")
        return 0
    path = args.spec_extra[-1] / "manuals.yaml"
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("a", encoding="utf-8") as file:
        file.write(entry if path.stat().st_size else MANUALS_HEADER + entry)
    print(f"added manual {args.id} to {path}")
    return 0


def _new_sentence(spec, args: argparse.Namespace) -> int:
    from .scaffold import ScaffoldError, sentence, sentence_path
    if not args.manual:
        print(f"new {args.what}: give --manual (the manual that documents it)", file=sys.stderr)
        return 2
    kind = "command" if args.what == "command" else "output"
    try:
        text = sentence(spec, args.id, args.manual, kind, args.address)
    except ScaffoldError as err:
        print(f"new {args.what}: {err}", file=sys.stderr)
        return 2
    if not args.spec_extra:
        print(text, end="")
        return 0
    path = sentence_path(args.spec_extra[-1], args.id)
    if path.exists():
        print(f"new {args.what}: {path} exists", file=sys.stderr)
        return 2
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    print(f"created {path}")
    return 0


def _write(spec, args: argparse.Namespace) -> int:
    from .render import render_all
    from .naming import NamingError, check_names, rename_files
    from .selection import SelectionError, parse_selector, subset

    custom = args.only or args.prefix or args.namespace
    if args.out is None:
        if CHECKOUT is None:
            print(f"{args.verb}: give --out DIR (the generator is not running from a checkout with its generated/)",
                  file=sys.stderr)
            return 2
        if custom or args.spec_extra:
            print(f"{args.verb}: --only, --prefix, --namespace and --spec-extra need --out DIR (generated/ is the "
                  "full default copy)", file=sys.stderr)
            return 2
        args.out = CHECKOUT / "generated"
        # the framing table the runtimes hold (generator/emit_framing.py), from the checkout's spec
        from . import emit_framing
        if args.verb == "generate":
            for path in emit_framing.write(spec):
                print(f"updated {path.relative_to(CHECKOUT)}")
        elif stale := emit_framing.stale(spec):
            for path in stale:
                print(f"stale: {path.relative_to(CHECKOUT)}", file=sys.stderr)
            print("runtime/ is out of date: run `make` (python3 -m generator generate)", file=sys.stderr)
            return 1
    try:
        check_names(args.prefix, args.namespace)
        if args.only:
            spec = subset(spec, parse_selector(args.only))
    except (SelectionError, NamingError) as err:
        print(f"{args.verb}: {err}", file=sys.stderr)
        return 2
    files = rename_files(render_all(spec), spec, args.prefix, args.namespace)

    out: Path = args.out
    quiet = getattr(args, "quiet", False)
    created, updated, unchanged = [], [], 0
    for rel, content in sorted(files.items()):
        path = out / rel
        data = content.encode("utf-8")
        old = path.read_bytes() if path.exists() else None
        if old == data:
            unchanged += 1
            continue
        (updated if old is not None else created).append(rel)
        if args.verb == "generate":
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)
            if not quiet:
                print(f"{'updated' if old is not None else 'created'} {out.name}/{rel}")
    extra = sorted(p.relative_to(out).as_posix() for p in out.rglob("*")
                   if p.is_file() and p.relative_to(out).as_posix() not in files and not _ignored(p, out)) \
        if out.is_dir() else []
    if args.verb == "generate":
        for rel in extra:
            (out / rel).unlink()
            if not quiet:
                print(f"removed {out.name}/{rel}")
        _remove_empty_dirs(out)
        if created or updated or extra:
            print(f"{out.name}/: {len(created)} created, {len(updated)} updated, {len(extra)} removed, "
                  f"{unchanged} unchanged")
        else:
            print(f"nothing changed ({len(files)} files)")
        return 0
    for rel in created + updated:
        print(f"stale: {out.name}/{rel}", file=sys.stderr)
    for rel in extra:
        print(f"not generated by the spec: {out.name}/{rel}", file=sys.stderr)
    if created or updated or extra:
        print(f"{out.name}/ is out of date: run `make` (python3 -m generator generate)", file=sys.stderr)
        return 1
    print(f"{out.name}/ is up to date ({len(files)} files)")
    return 0


def _ignored(path: Path, out: Path) -> bool:
    """Build products that tools leave inside generated/ (cargo, Python caches, pip builds)."""
    parts = path.relative_to(out).parts
    return any(p in ("target", "__pycache__", ".pytest_cache", "Cargo.lock", "build") or p.endswith(".egg-info")
               for p in parts) or path.suffix == ".pyc"


def _remove_empty_dirs(out: Path) -> None:
    for path in sorted((p for p in out.rglob("*") if p.is_dir()), key=lambda p: len(p.parts), reverse=True):
        if not any(path.iterdir()):
            path.rmdir()
