#!/usr/bin/env python3
"""The manual's key tables against the keys grainflow's scene readers accept, so neither can drift.

    manual_keys_test.py GRAINFLOW REPOSITORY

Runs `grainflow check SCENE --keys` on every shipped scene (scenes/**/*.toml) and on the scenes of
tests/keys/, which take the branches no shipped scene takes (pair and wall overrides of each law, periodic
y, cylinder regions, a liquid's solver table, ...); check lists each key the
scene's systems asked for, set in the file or left at its default, and reads the key tables of
docs/manual/*.md (a heading "### `[section]`", or "### `[section] model = ...`" for one law's keys, followed by a
table whose first column is "key"; a section's tables together list its keys). Fails when
  - a key some scene's readers accept is in no table of its section (undocumented), or
  - a table lists a key that no scene's readers ask for (documented but not read: a stale row, or a branch
    of a reader that no scene takes; then add a scene to tests/keys/ that takes it).
Paths are compared with array indices dropped (wall[2].omega is [[wall]] omega); a table key written
`count.<species>` stands for any one name in that place.
"""
import pathlib
import re
import subprocess
import sys

HEADING = re.compile(r"^### `(\[\[?)([A-Za-z0-9_.]+)(\]\]?)( [^`]*)?`\s*$")  # "[contact] model = ..." too
ROW = re.compile(r"^\|\s*`([^`]+)`\s*\|")


def manual_tables(manual):
    """{section path as the readers spell it, arrays as 'name[]'}: {key pattern: 'page:line'}."""
    tables = {}
    for page in sorted(manual.glob("*.md")):
        lines = page.read_text().splitlines()
        i = 0
        while i < len(lines):
            m = HEADING.match(lines[i])
            i += 1
            if not m:
                continue
            while i < len(lines) and not lines[i].startswith(("|", "#")):
                i += 1  # a sentence or two between the heading and its table
            if i >= len(lines) or not lines[i].startswith("| key |"):
                continue
            section = m.group(2) + ("[]" if m.group(1) == "[[" else "")
            keys = tables.setdefault(section, {})
            i += 2  # header, rule
            while i < len(lines) and lines[i].startswith("|"):
                r = ROW.match(lines[i])
                if r:
                    keys.setdefault(r.group(1), f"{page.name}:{i + 1}")
                i += 1
    return tables


# Override tables that take the keys of another section's tables besides their own rows (the manual says so
# under their heading): [contact.wall] and [[contact.pair]] take the scene's law's [contact] keys.
INHERITS = {"contact.wall": "contact", "contact.pair[]": "contact"}


def pattern(key):
    return re.compile("^" + re.sub(r"<[^>]*>", r"[^.]+", re.escape(key)) + "$")


def scene_keys(grainflow, root):
    """{normalised path: first scene that reads it}, and the scenes that check refused."""
    read, refused = {}, []
    for scene in sorted((root / "scenes").rglob("*.toml")) + sorted((root / "tests/keys").glob("*.toml")):
        p = subprocess.run([grainflow, "check", str(scene), "--keys"], capture_output=True, text=True, timeout=600)
        if p.returncode != 0:
            refused.append(f"{scene.relative_to(root)}: exit {p.returncode}: {p.stderr.strip()[:300]}")
            continue
        for line in p.stdout.splitlines():
            if line.startswith("key: "):
                path = re.sub(r"\[\d+\]", "[]", line[5:].strip())
                read.setdefault(path, str(scene.relative_to(root)))
    return read, refused


def section_of(path, sections):
    """The longest section that path lies in, and the key within it; (None, path) at the top level."""
    best = None
    for s in sections:
        if path.startswith(s + ".") and (best is None or len(s) > len(best)):
            best = s
    return (best, path[len(best) + 1:]) if best else (None, path)


def main():
    grainflow, root = sys.argv[1], pathlib.Path(sys.argv[2])
    tables = manual_tables(root / "docs/manual")
    read, refused = scene_keys(grainflow, root)
    problems = list(refused)
    matched = {(s, k): False for s, keys in tables.items() for k in keys}
    for path, scene in sorted(read.items()):
        section, key = section_of(path, tables)
        if section is None:
            if path in tables or path.rstrip("[]") + "[]" in tables or any(s.startswith(path + ".") for s in tables):
                continue  # a section's own name
            problems.append(f"undocumented: section or key '{path}' (read for {scene}) has no key table in docs/manual")
            continue
        hits = [k for k in tables[section] if pattern(k).match(key)]
        if not hits and section in INHERITS:
            section = INHERITS[section]
            hits = [k for k in tables.get(section, {}) if pattern(k).match(key)]
        for k in hits:
            matched[section, k] = True
        # A key that holds a sub-table documented by its dotted keys (region, count, solver), or by a table of
        # its own ([contact.wall], [[analysis.repose]]), needs no row.
        own = f"{section}.{key}"
        if not hits and not any(k.startswith(key + ".") for k in tables[section]) and \
                own not in tables and own + "[]" not in tables:
            problems.append(f"undocumented: '{key}' of [{section}] (read for {scene}) is in no key table of docs/manual")
    for (section, key), hit in sorted(matched.items()):
        if not hit:
            problems.append(f"not read: '{key}' of [{section}] ({tables[section][key]}) is asked for by no scene's "
                            "readers in scenes/ or tests/keys/")
    scenes = len(list((root / "scenes").rglob("*.toml"))) + len(list((root / "tests/keys").glob("*.toml")))
    print(f"{len(read)} key paths read by {scenes} scenes; "
          f"{sum(len(k) for k in tables.values())} keys in {len(tables)} manual tables")
    if problems:
        print("\n".join(problems))
        print(f"{len(problems)} differences between the manual's key tables and the readers")
        sys.exit(1)
    print("the manual's key tables and the readers agree")


if __name__ == "__main__":
    main()
