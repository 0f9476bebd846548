"""JSON Schemas of the telemetry messages, read from their LCM definitions (lcm_types/*.lcm,
installed under share/harvest/lcm): the .lcm files are the one source of truth of the
messages, so the schema a viewer shows carries their field types, array sizes and comments.

Only what lcm_types/ uses is understood: one `package`, `struct`s of primitive, string or
struct fields, fixed or variable array dimensions, `//` comments (one alone on a line after
a field continues that field's). Anything else raises ValueError naming the file and line.
"""

import json
import os
import re

from harvest import resources

_PRIMITIVE = {
    "int8_t": "integer",
    "int16_t": "integer",
    "int32_t": "integer",
    "int64_t": "integer",
    "byte": "integer",
    "float": "number",
    "double": "number",
    "string": "string",
    "boolean": "boolean",
}
_FIELD = re.compile(r"^(\w+)\s+(\w+)((?:\s*\[\s*\w+\s*\])*)\s*;$")
_STRUCT = re.compile(r"^struct\s+(\w+)\s*\{?$")


def default_dir():
    return resources.path("lcm_defs")


def parse(path):
    """(struct name, [(field, type, [dims], comment)]) of one .lcm file."""
    name, fields = None, []
    with open(path) as f:
        for lineno, raw in enumerate(f, 1):
            code, _, comment = raw.partition("//")
            code = code.strip()
            if not code and comment.strip() and fields:
                # a field's comment continued on the next line
                f = fields[-1]
                fields[-1] = (f[0], f[1], f[2], f"{f[3]} {comment.strip()}".strip())
                continue
            if not code or code in ("{", "}") or code.startswith("package "):
                continue
            m = _STRUCT.match(code)
            if m and name is None:
                name = m.group(1)
                continue
            m = _FIELD.match(code)
            if not m or name is None:
                raise ValueError(f"{path}:{lineno}: not understood: {code!r}")
            dims = re.findall(r"\[\s*(\w+)\s*\]", m.group(3))
            fields.append((m.group(2), m.group(1), dims, comment.strip()))
    if name is None:
        raise ValueError(f"{path}: no struct")
    return name, fields


def load(folder=None):
    """Dict struct name -> fields of every .lcm file in `folder`."""
    folder = folder or default_dir()
    structs = {}
    for entry in sorted(os.listdir(folder)):
        if entry.endswith(".lcm"):
            name, fields = parse(os.path.join(folder, entry))
            structs[name] = fields
    if not structs:
        raise ValueError(f"{folder}: no .lcm files")
    return structs


def json_schema(structs, name):
    """A JSON Schema (draft 2020-12) of struct `name`, nested structs inline."""

    def one(type_name):
        if type_name in _PRIMITIVE:
            return {"type": _PRIMITIVE[type_name]}
        if type_name not in structs:
            raise ValueError(f"struct {name}: unknown type {type_name}")
        return obj(type_name)

    def obj(struct):
        props = {}
        for field, type_name, dims, comment in structs[struct]:
            s = one(type_name)
            for dim in reversed(dims):
                s = {"type": "array", "items": s}
                if dim.isdigit():
                    s["minItems"] = s["maxItems"] = int(dim)
            if comment:
                s["description"] = comment
            props[field] = s
        return {"type": "object", "title": struct, "properties": props, "required": list(props)}

    schema = obj(name)
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    return schema


def schema_of(structs, type_name):
    """(schema name, JSON Schema as bytes) of LCM type `type_name`: how the MCAP export and
    the live view name and describe a channel of that type."""
    return f"harvest.{type_name}", json.dumps(json_schema(structs, type_name)).encode()


def message_json(msg):
    """A decoded lcm-gen message as the bytes of its JSON (to_json)."""
    return json.dumps(to_json(msg)).encode()


def to_json(msg):
    """A decoded lcm-gen message as plain JSON values (nested structs as objects)."""
    if hasattr(msg, "__slots__"):
        return {k: to_json(getattr(msg, k)) for k in msg.__slots__}
    if isinstance(msg, (list, tuple)):
        return [to_json(v) for v in msg]
    if isinstance(msg, bytes):
        return list(msg)
    return msg
