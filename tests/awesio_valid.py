"""Checks of awesIO documents for the tests: valid against the published schema, and
against it as awesIO's own validator applies it by default."""

from jsonschema import Draft7Validator

from fem_tether.io.awesio import kind_of, layout_of, schema, schema_errors


def restrictive(node):
    """A schema as awesIO's own validator applies it by default (``restrictive=True``): every
    object schema reached through ``properties``, ``items`` and the combinators (not
    ``definitions``, ``if``/``then``) that does not say otherwise admits no other keys."""
    if not isinstance(node, dict):
        return node
    node = dict(node)
    if (node.get("type") == "object" or "properties" in node) and "additionalProperties" not in node:
        node["additionalProperties"] = False
    if isinstance(node.get("properties"), dict):
        node["properties"] = {k: restrictive(v) for k, v in node["properties"].items()}
    for key in ("items", "additionalItems"):
        if key in node:
            node[key] = restrictive(node[key])
    for key in ("oneOf", "anyOf", "allOf"):
        if key in node:
            node[key] = [restrictive(v) for v in node[key]]
    return node


def assert_valid(document: dict, layout: str | None = None) -> None:
    """``document`` validates against its schema (of its layout, which is ``layout`` if given), as
    published and as awesIO's validator applies it."""
    kind = kind_of(document, "document")
    found = layout_of(document, kind, "document")
    assert layout in (None, found), found
    assert schema_errors(document, kind, found) == []
    assert list(Draft7Validator(restrictive(schema(kind, found))).iter_errors(document)) == []


def schema_fields(node, root, prefix="", indexed=False):
    """Every field a document of the schema ``root`` can hold: dotted paths through
    ``properties``, ``$ref``s to its definitions and the ``allOf`` branches' ``then``; with
    ``indexed``, through the items of arrays of objects too, as ``list[0]``."""
    if "$ref" in node:
        node = root["definitions"][node["$ref"].removeprefix("#/definitions/")]
    branches = [node] + [b["then"] for b in node.get("allOf", []) if "then" in b]
    merged = {}
    for branch in branches:
        for name, sub in branch.get("properties", {}).items():
            merged.setdefault(name, []).append(sub)
    found = set()
    for name, subs in merged.items():
        path = f"{prefix}.{name}" if prefix else name
        deeper = set().union(*(schema_fields(sub, root, path, indexed) for sub in subs))
        if indexed:
            items = [sub["items"] for sub in subs if isinstance(sub.get("items"), dict)
                     and ("$ref" in sub["items"] or "properties" in sub["items"])]
            deeper |= set().union(*(schema_fields(item, root, f"{path}[0]", indexed) for item in items))
        found |= deeper or {path}
    return found
