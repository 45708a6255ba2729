"""awesIO documents: read, check against the published schemas, write.

awesIO (IEA Wind Task 48, "AWE system IO", v0.1.0) describes an airborne
wind energy system and its results in YAML documents of four kinds
(``system``, ``wind_resource``, ``power_curves``, ``operational_constraints``),
each opening with a ``metadata`` block that names its schema
(``metadata.schema: power_curves_schema.yml``) and ``awesIO_version``.  The
schemas are JSON Schemas (draft 07) written as YAML; the copies in
``awesio_schemas/`` are the published ones, byte for byte (their provenance
and licence: ``awesio_schemas/PROVENANCE.md``).  The schema is the contract:
example files of awesIO disagree with their schema in places (``length``
where the schema asks ``length_m``), and a document is read only if it validates.

YAML is read as YAML 1.2 reads numbers: ``1.0e9`` is a float (PyYAML, a
YAML 1.1 parser, reads it as the string "1.0e9", which the schemas refuse;
awesIO's own tools parse YAML 1.2).

Two layouts of v0.1.0 exist, both stating ``awesIO_version: 0.1.0`` and the same
``metadata.schema`` file name: the fork ufechner7/awesIO's, whose keys carry
units (``reference_height_m``), the one fem-tether writes by default; and
awegroup/awesIO's later schemas, keys without units (``reference_height``) and,
for ``power_curves`` and ``system``, another structure (lists of kites and
tethers; a curve's points as a list of wind speeds, each with its power).
A document's layout is told by its keys (:func:`layout_of`): those one
layout's schema defines and the other's does not.  A document with keys of
both is ambiguous and refused, naming one of each.

>>> kind_of({"metadata": {"schema": "power_curves_schema.yml"}}, "x.yml")
'power_curves'
>>> yaml_text({"metadata": {"name": "n"}}).splitlines()[0].startswith("# fem-tether")
True
"""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path
from typing import Any

from fem_tether.core.atomic import generator_tag
from fem_tether.core.errors import InputError
from fem_tether.core.inputfile import read_text

#: The awesIO version whose schemas are shipped and whose documents are written.
AWESIO_VERSION = "0.1.0"

#: The shipped schemas (the published v0.1.0 files, unchanged): the fork's here, awegroup's in ``awegroup/``.
SCHEMAS_DIR = Path(__file__).parent / "awesio_schemas"

#: The layouts of awesIO 0.1.0, each with where its schemas come from (awesio_schemas/PROVENANCE.md).
LAYOUTS = {"ufechner7": "ufechner7/awesIO v0.1.0, keys with units",
           "awegroup": "awegroup/awesIO 120b741 and 8841a62, keys without units"}

#: The layout fem-tether writes unless told otherwise.
DEFAULT_LAYOUT = "ufechner7"

#: The document kinds, each checked by ``KIND_schema.yml``.
KINDS = ("system", "wind_resource", "power_curves", "operational_constraints")

#: Schema errors named in one line before "(and N more)".
ERRORS_SHOWN = 1

#: YAML 1.2's floats (1.0e9, 1e9, .5, -2.5E-3; not 1.0e+9 alone): PyYAML's resolver misses the ones
#: without a signed exponent or a dot.
_FLOAT_1_2 = re.compile(r"^[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?$|^[-+]?\.(inf|Inf|INF)$|^\.(nan|NaN|NAN)$")


class AwesioError(InputError):
    """An awesIO document is unreadable, of another kind, or not valid against its schema."""


def _loader():
    """PyYAML's safe loader with YAML 1.2's floats (C-accelerated if available)."""
    import yaml

    base = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

    class Loader(base):  # type: ignore[valid-type, misc]
        pass

    Loader.yaml_implicit_resolvers = {k: [r for r in v if r[0] != "tag:yaml.org,2002:float"]
                                      for k, v in base.yaml_implicit_resolvers.items()}
    Loader.add_implicit_resolver("tag:yaml.org,2002:float", _FLOAT_1_2, list("-+0123456789."))
    return Loader


def parse_yaml(text: str, source: str) -> Any:
    """The YAML ``text`` (YAML 1.2 floats); :class:`AwesioError` naming ``source`` if it does not parse."""
    import yaml

    try:
        return yaml.load(text, Loader=_loader())
    except yaml.YAMLError as exc:
        raise AwesioError(f"{source}: not YAML: {' '.join(str(exc).split())}") from None


def schema_path(kind: str, layout: str = DEFAULT_LAYOUT) -> Path:
    """The shipped schema file of documents of ``kind`` in ``layout`` (one of :data:`LAYOUTS`)."""
    return (SCHEMAS_DIR if layout == DEFAULT_LAYOUT else SCHEMAS_DIR / layout) / f"{kind}_schema.yml"


def layouts_of(kind: str) -> list[str]:
    """The layouts whose ``kind`` schema is shipped (awegroup's: ``wind_resource``, ``power_curves``
    and ``system``)."""
    return [layout for layout in LAYOUTS if schema_path(kind, layout).is_file()]


@cache
def schema(kind: str, layout: str = DEFAULT_LAYOUT) -> dict:
    """The published JSON Schema of documents of ``kind`` (one of :data:`KINDS`) in ``layout``."""
    return parse_yaml(schema_path(kind, layout).read_text(encoding="utf-8"), f"{kind} ({layout})")


def _schema_keys(node: dict, prefix: str = "", required: bool = True) -> dict[str, bool]:
    """The keys ``node`` defines, as dotted paths through objects and arrays (``clusters.id``),
    each with whether it is required (along its whole path)."""
    keys: dict[str, bool] = {}
    for key, sub in node.get("properties", {}).items():
        path, needed = f"{prefix}{key}", required and key in node.get("required", ())
        keys[path] = needed
        for item in (sub, sub.get("items")):
            if isinstance(item, dict):
                keys.update(_schema_keys(item, f"{path}.", needed))
    return keys


def _document_keys(node: Any, prefix: str = "") -> set[str]:
    """The keys of ``node`` as dotted paths through mappings and lists (as :func:`_schema_keys`)."""
    if isinstance(node, list):
        return set().union(*(_document_keys(item, prefix) for item in node))
    if not isinstance(node, dict):
        return set()
    return set().union(*({f"{prefix}{key}"} | _document_keys(sub, f"{prefix}{key}.") for key, sub in node.items()))


@cache
def layout_keys(kind: str, layout: str) -> tuple[str, ...]:
    """The keys of ``layout``'s ``kind`` schema that no other layout's defines, required ones first."""
    own = _schema_keys(schema(kind, layout))
    others = set().union(*(_schema_keys(schema(kind, other)) for other in layouts_of(kind) if other != layout))
    return tuple(sorted((k for k in own if k not in others), key=lambda k: (not own[k], k)))


def layout_of(document: Any, kind: str, source: str) -> str:
    """The layout of the ``kind`` document ``document``: the one whose own keys
    (:func:`layout_keys`) it has; :class:`AwesioError` naming ``source`` and the keys if it
    has keys of two layouts or of none."""
    layouts = layouts_of(kind)
    if len(layouts) == 1:
        return layouts[0]
    keys = _document_keys(document)
    found = {layout: [k for k in layout_keys(kind, layout) if k in keys] for layout in layouts}
    chosen = [layout for layout in layouts if found[layout]]
    if len(chosen) == 1:
        return chosen[0]
    if chosen:
        named = " and ".join(f"'{found[layout][0]}' ({LAYOUTS[layout]})" for layout in chosen)
        raise AwesioError(f"{source}: ambiguous awesIO {kind} document: it has keys of two layouts, {named}; "
                          "a document follows one")
    named = " nor ".join(f"'{layout_keys(kind, layout)[0]}' ({LAYOUTS[layout]})" for layout in layouts)
    raise AwesioError(f"{source}: awesIO {kind} document of no known layout: it has neither {named}")


def schema_errors(document: Any, kind: str, layout: str = DEFAULT_LAYOUT) -> list[str]:
    """Where ``document`` breaks the ``kind`` schema of ``layout``, one ``at 'a.b.0': message`` each,
    in document order."""
    from jsonschema import Draft7Validator

    errors = sorted(Draft7Validator(schema(kind, layout)).iter_errors(document), key=lambda e: [str(p) for p in e.path])
    return [f"at '{'.'.join(str(p) for p in e.path) or '(top)'}': {e.message}" for e in errors]


def kind_of(document: Any, source: str) -> str:
    """The kind a document's ``metadata.schema`` names; :class:`AwesioError` if it names none."""
    metadata = document.get("metadata") if isinstance(document, dict) else None
    name = metadata.get("schema") if isinstance(metadata, dict) else None
    kind = name.removesuffix("_schema.yml") if isinstance(name, str) else None
    if kind not in KINDS:
        raise AwesioError(f"{source}: not an awesIO document: metadata.schema is {name!r} "
                          f"(awesIO {AWESIO_VERSION}: {', '.join(k + '_schema.yml' for k in KINDS)})")
    return kind


def check(document: Any, kind: str, source: str, layout: str = DEFAULT_LAYOUT) -> None:
    """:class:`AwesioError` naming ``source`` and the first place ``document`` breaks the ``kind``
    schema of ``layout``."""
    errors = schema_errors(document, kind, layout)
    if errors:
        more = f" (and {len(errors) - ERRORS_SHOWN} more)" if len(errors) > ERRORS_SHOWN else ""
        raise AwesioError(f"{source}: not a valid awesIO {kind} document "
                          f"({kind}_schema.yml of {LAYOUTS[layout]}): {'; '.join(errors[:ERRORS_SHOWN])}{more}")


def read_layout_document(path: str | Path, kind: str | None = None) -> tuple[str, str, dict]:
    """The awesIO document at ``path``, its kind and its layout (:func:`layout_of`), checked
    against its layout's schema (and, if given, to be of ``kind``); :class:`AwesioError` naming
    the file otherwise."""
    document = parse_yaml(read_text(path, AwesioError), str(path))
    found = kind_of(document, str(path))
    if kind is not None and found != kind:
        raise AwesioError(f"{path}: an awesIO {found} document, where one of {kind}_schema.yml is expected")
    layout = layout_of(document, found, str(path))
    check(document, found, str(path), layout)
    return found, layout, document


def read_document(path: str | Path, kind: str | None = None) -> tuple[str, dict]:
    """The awesIO document at ``path`` and its kind, as :func:`read_layout_document`, refused
    unless in the layout fem-tether maps field by field (:data:`DEFAULT_LAYOUT`)."""
    found, layout, document = read_layout_document(path, kind)
    if layout != DEFAULT_LAYOUT:
        raise AwesioError(f"{path}: an awesIO {found} document of {LAYOUTS[layout]}: fem-tether reads this kind "
                          f"in the layout of {LAYOUTS[DEFAULT_LAYOUT]} only (docs/awesio.md)")
    return found, document


def yaml_text(document: dict) -> str:
    """``document`` as YAML (block style, keys in the document's order), its first line
    the comment ``# fem-tether VERSION`` that marks the file as ours."""
    import yaml

    body = yaml.dump(document, Dumper=getattr(yaml, "CSafeDumper", yaml.SafeDumper), sort_keys=False,
                     default_flow_style=False, allow_unicode=True, width=100)
    return f"# {generator_tag()}: awesIO {AWESIO_VERSION} document\n{body}"
