"""Griffe extension for the API reference: every default shown comes from the code.

mkdocstrings shows a default twice: in the signature (read from the source) and in the
*Default* column of the parameters table (read from the docstring). The docstring parser fills
that column itself, and gets it wrong in two ways: a docstring line that documents several
parameters at once (``terms_per_decade, smoothing, nu``) gives all of them the first one's
default, and a line of choices (``shift : {"wlf", "arrhenius"}``) gives its first choice as the
default whatever the code says. This extension sets every documented parameter's default from
the function's own signature, and a signature default that is a bare name (``level=SEED_LEVEL``)
to the value that name has when the module is imported, so that a reader sees ``0.476`` rather
than a constant to look up. ``tests/docs/test_api_defaults.py`` checks the result.
"""

from __future__ import annotations

import importlib
import re

import griffe

_NAME = re.compile(r"^[A-Za-z_][\w.]*$")
_KEEP = {"None", "True", "False"}


def live_object(obj):
    """The imported Python object behind the griffe object ``obj``, or None."""
    module = obj
    while not module.is_module:
        module = module.parent
    try:
        target = importlib.import_module(module.path)
        for part in obj.path[len(module.path) + 1 :].split("."):
            if part:
                target = getattr(target, part)
    except (ImportError, AttributeError):
        return None
    return target


def _live_default(owner, name):
    """repr of the default of parameter ``name`` of the live callable ``owner``, or None."""
    import inspect

    try:
        parameter = inspect.signature(owner).parameters[name]
    except (TypeError, ValueError, KeyError):
        return None
    if parameter.default is inspect.Parameter.empty:
        return None
    text = repr(parameter.default)
    return text if len(text) <= 40 and " at 0x" not in text else None


def _resolve_names(obj):
    """Signature defaults written as bare names -> the values they hold."""
    parameters = getattr(obj, "parameters", None)
    if not parameters:
        return
    owner = None
    for p in parameters:
        text = str(p.default) if p.default is not None else ""
        if not _NAME.match(text) or text in _KEEP:
            continue
        owner = owner if owner is not None else live_object(obj)
        value = _live_default(owner, p.name) if owner is not None else None
        if value is not None:
            p.default = value


def documented_defaults(obj):
    """Set the parameters table's defaults of ``obj`` from its signature; return the table."""
    parameters = getattr(obj, "parameters", None)
    if obj.docstring is None or not parameters:
        return []
    rows = []
    for section in obj.docstring.parsed:  # parsed once, cached: the page renders these
        if section.kind is not griffe.DocstringSectionKind.parameters:
            continue
        for row in section.value:
            if row.name in parameters:
                default = parameters[row.name].default
                row.value = None if default is None else default
            rows.append(row)
    return rows


class DefaultsFromCode(griffe.Extension):
    """Signature and table defaults of functions and classes, from the code."""

    def on_function(self, *, func, loader, **kwargs):
        _resolve_names(func)
        documented_defaults(func)

    def on_class(self, *, cls, loader, **kwargs):
        _resolve_names(cls)
        documented_defaults(cls)
