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

#: The shipped schemas (the published v0.1.0 files, unchanged).
SCHEMAS_DIR = Path(__file__).parent / "awesio_schemas"

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


@cache
def schema(kind: str) -> dict:
    """The published JSON Schema of documents of ``kind`` (one of :data:`KINDS`)."""
    return parse_yaml((SCHEMAS_DIR / f"{kind}_schema.yml").read_text(encoding="utf-8"), kind)


def schema_errors(document: Any, kind: str) -> list[str]:
    """Where ``document`` breaks the ``kind`` schema, one ``at 'a.b.0': message`` each, in document order."""
    from jsonschema import Draft7Validator

    errors = sorted(Draft7Validator(schema(kind)).iter_errors(document), key=lambda e: [str(p) for p in e.path])
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


def check(document: Any, kind: str, source: str) -> None:
    """:class:`AwesioError` naming ``source`` and the first place ``document`` breaks the ``kind`` schema."""
    errors = schema_errors(document, kind)
    if errors:
        more = f" (and {len(errors) - ERRORS_SHOWN} more)" if len(errors) > ERRORS_SHOWN else ""
        raise AwesioError(f"{source}: not a valid awesIO {kind} document "
                          f"({kind}_schema.yml, awesIO {AWESIO_VERSION}): {'; '.join(errors[:ERRORS_SHOWN])}{more}")


def read_document(path: str | Path, kind: str | None = None) -> tuple[str, dict]:
    """The awesIO document at ``path`` and its kind, checked against its schema (and, if
    given, to be of ``kind``); :class:`AwesioError` naming the file otherwise."""
    document = parse_yaml(read_text(path, AwesioError), str(path))
    found = kind_of(document, str(path))
    if kind is not None and found != kind:
        raise AwesioError(f"{path}: an awesIO {found} document, where one of {kind}_schema.yml is expected")
    check(document, found, str(path))
    return found, document


def yaml_text(document: dict) -> str:
    """``document`` as YAML (block style, keys in the document's order), its first line
    the comment ``# fem-tether VERSION`` that marks the file as ours."""
    import yaml

    body = yaml.dump(document, Dumper=getattr(yaml, "CSafeDumper", yaml.SafeDumper), sort_keys=False,
                     default_flow_style=False, allow_unicode=True, width=100)
    return f"# {generator_tag()}: awesIO {AWESIO_VERSION} document\n{body}"
