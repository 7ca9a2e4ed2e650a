#!/usr/bin/env python3
"""Tests of scripts/scene_reference.py: docs/scene-reference.md is what the script generates,
and it has a table for every object of the schema listing exactly that object's keys, with
the unit and default the schema gives."""
import json
import pathlib
import re
import sys
import unittest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import scene_reference  # noqa: E402


def objects(node, out):
    """Every "properties" map of the schema."""
    if isinstance(node, dict):
        if isinstance(node.get("properties"), dict):
            out.append(node["properties"])
        for value in node.values():
            objects(value, out)
    elif isinstance(node, list):
        for value in node:
            objects(value, out)
    return out


def tables(text):
    """{tuple of keys: [row cells]} of every key table of the reference."""
    out, rows = {}, []
    for line in text.splitlines() + [""]:
        m = re.match(r"\| `([^`]+)` \|(.*)\|$", line)
        if m:
            rows.append([m.group(1)] + [c.strip() for c in m.group(2).split(" | ")])
        elif rows:
            out[tuple(r[0] for r in rows)] = rows
            rows = []
    return out


class SceneReference(unittest.TestCase):
    def setUp(self):
        self.schema = json.loads((ROOT / "schema" / "scene.schema.json").read_text())
        self.text = scene_reference.generate(ROOT)

    def test_the_committed_reference_is_generated(self):
        self.assertEqual((ROOT / "docs" / "scene-reference.md").read_text(), self.text,
                         "run scripts/scene_reference.py")

    def test_every_object_of_the_schema_has_its_table(self):
        found = tables(self.text)
        for props in objects(self.schema, []):
            keys = tuple(props)
            self.assertIn(keys, found, f"no table with the keys {keys}")
            for row in found[keys]:
                prop = props[row[0]]
                if "x-unit" in prop:
                    self.assertEqual(row[2], prop["x-unit"], row[0])
                if "default" in prop:
                    self.assertEqual(row[3], f"`{json.dumps(prop['default'])}`", row[0])

    def test_every_section_link_resolves(self):
        ids = set(re.findall(r'<a id="([^"]+)"></a>', self.text))
        for target in re.findall(r"\]\(#([^)]+)\)", self.text):
            self.assertIn(target, ids)


if __name__ == "__main__":
    unittest.main()
