"""The case package's modules depend on each other in one direction: validate does not import the
model (which builds the Case from validated values), and nothing imports inside a function."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

CASE = Path(__file__).parents[3] / "solver" / "case"


def _imports(tree: ast.AST) -> list[str]:
    names = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            names.append("." * node.level + (node.module or ""))
        elif isinstance(node, ast.Import):
            names += [alias.name for alias in node.names]
    return names


def test_validate_does_not_import_the_model():
    tree = ast.parse((CASE / "validate.py").read_text())
    imported = _imports(tree)
    assert not [name for name in imported if name.endswith("model")], imported


@pytest.mark.parametrize("module", sorted(p.name for p in CASE.glob("*.py")))
def test_no_function_level_imports(module):
    tree = ast.parse((CASE / module).read_text())
    inside = [
        node.lineno
        for function in ast.walk(tree)
        if isinstance(function, ast.FunctionDef | ast.AsyncFunctionDef)
        for node in ast.walk(function)
        if isinstance(node, ast.Import | ast.ImportFrom)
    ]
    assert inside == [], f"{module}: imports inside functions at lines {inside}"
