"""Help that stands alone: numpydoc docstrings for every public function and class (each
parameter with its meaning, unit or range and default; returns, raises, an example), the
examples run, type stubs that match the runtime signatures, dir(result) with the columns,
wavy.__version__ and a readable repr."""

import ast
import doctest
import importlib.metadata
import inspect
import re
from pathlib import Path

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc

import wavy
from wavy import _result, _wavy

FUNCTIONS = [wavy.solve, wavy.run, wavy.westergaard, wavy.westergaard_inverse, wavy.wnl,
             wavy.wnl_inverse, wavy.Result.to_pandas]
PACKAGE = Path(wavy.__file__).parent


def documented(doc, section="Parameters"):
    """name → description text of a numpydoc section (``a, b : int`` documents both)."""
    out = {}
    for p in doc[section]:
        for name in p.name.split(","):
            out[name.strip()] = " ".join(p.desc)
    return out


@pytest.mark.parametrize("function", FUNCTIONS, ids=lambda f: f.__qualname__)
def test_every_parameter_is_documented_with_its_default(function):
    doc = FunctionDoc(function)
    params = documented(doc)
    signature = [p for p in inspect.signature(function).parameters.values() if p.name != "self"]
    assert list(params) == [p.name for p in signature]
    for p in signature:
        text = params[p.name]
        assert len(text) > 20, (p.name, text)
        if p.default is inspect.Parameter.empty:
            assert "No default" in text, (p.name, text)
        else:
            default = p.default if isinstance(p.default, str) else repr(p.default)
            assert re.search(rf"Default {re.escape(str(default))}\b|Default \"{re.escape(str(default))}\"", text), (p.name, text)
    assert doc["Summary"] and doc["Returns"] and doc["Examples"]
    if function is not wavy.Result.to_pandas:
        raised = {p.type or p.name for p in doc["Raises"]}
        assert {"TypeError", "ValueError"} <= raised, raised


def test_the_extension_arguments_are_each_documented_in_solve():
    params = documented(FunctionDoc(wavy.solve))
    extension = inspect.signature(_wavy.solve).parameters
    assert set(extension) <= set(params), set(extension) - set(params)
    # the defaults the docstring states are the library's
    for name, value in _wavy.SOLVE_DEFAULTS.items():
        assert f"Default None: {value!r}" in params[name], (name, params[name])


def test_the_classes_document_their_columns_attributes_and_parameters():
    result = documented(ClassDoc(wavy.Result), "Attributes")
    assert set(wavy.COLUMNS) | {"error_estimate", "columns"} | set(_result.METADATA) <= set(result)
    error = ClassDoc(wavy.SolveError)
    assert list(documented(error)) == ["message", "reason", "partial"]
    assert {"reason", "partial", "a_over_lambda"} <= set(documented(error, "Attributes"))
    assert list(documented(ClassDoc(wavy.ExtrapolationWarning))) == ["message"]


def test_the_docstring_examples_run():
    # the public objects say they are wavy's (__module__), so doctest finds them all there
    failures, tried = doctest.testmod(wavy, optionflags=doctest.ELLIPSIS)
    assert tried >= 10 and failures == 0


def test_dir_of_a_result_lists_its_columns_and_its_repr_is_plain():
    r = wavy.solve(ar=0.3, mesh=8, until_a_over_lambda=0.3)
    assert set(r.columns) <= set(dir(r)) and set(_result.METADATA) <= set(dir(r))
    text = repr(r)
    assert text.startswith(f"<wavy.Result: {r.load_steps} load steps on mesh 8×4, last a/λ = ")
    assert "np." not in text and "float64" not in text


def test_the_version_is_the_package_version():
    assert wavy.__version__ == importlib.metadata.version("wavy")
    assert re.fullmatch(r"\d+\.\d+\.\d+", wavy.__version__)


def stub_signatures(path):
    """name → (positional names, keyword-only names) of every function of a stub file (the
    first overload of each)."""
    tree = ast.parse(path.read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.name not in out:
            out[node.name] = ([a.arg for a in node.args.args],
                              [a.arg for a in node.args.kwonlyargs])
    return out


def runtime_signature(function):
    params = inspect.signature(function).parameters.values()
    positional = [p.name for p in params if p.kind is p.POSITIONAL_OR_KEYWORD]
    keyword = [p.name for p in params if p.kind is p.KEYWORD_ONLY]
    return positional, keyword


def test_the_stubs_ship_and_match_the_runtime_signatures():
    assert (PACKAGE / "py.typed").is_file()
    stubs = stub_signatures(PACKAGE / "__init__.pyi")
    for name in wavy.__all__:
        obj = getattr(wavy, name)
        if inspect.isfunction(obj):
            assert stubs[name] == runtime_signature(obj), name
    extension = stub_signatures(PACKAGE / "_wavy.pyi")
    for name in ("law", "fit_domain", "solve", "run"):
        assert extension[name] == runtime_signature(getattr(_wavy, name)), name
    tree = ast.parse((PACKAGE / "__init__.pyi").read_text())
    result = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "Result")
    annotated = {n.target.id for n in result.body if isinstance(n, ast.AnnAssign)}
    assert set(wavy.COLUMNS) | {"error_estimate"} | set(_result.METADATA) <= annotated


def test_the_solve_call_in_python_md_shows_the_defaults():
    # docs/python.md shows one `wavy.solve(ar=…, …)` call with every other argument at its default
    text = (Path(__file__).parents[2] / "docs" / "python.md").read_text(encoding="utf-8")
    start = text.index("r = wavy.solve(ar=")
    call = ast.parse(text[start:text.index(")", start) + 1]).body[0].value
    shown = {k.arg: ast.literal_eval(k.value) for k in call.keywords}
    signature = inspect.signature(wavy.solve).parameters
    assert list(shown) == list(signature)
    for name, value in shown.items():
        if name != "ar":
            assert value == signature[name].default, (name, value, signature[name].default)


def test_the_build_backend_takes_the_tested_maturin():
    # python/requirements-test.txt pins the test tools; pyproject.toml's build requirement is its maturin
    python = Path(__file__).parents[1]
    pins = [line.split("#")[0].strip()
            for line in (python / "requirements-test.txt").read_text(encoding="utf-8").splitlines()]
    maturin = [p for p in pins if p.startswith("maturin")]
    build = re.search(r'^requires = \["([^"]+)"\]', (python / "pyproject.toml").read_text(encoding="utf-8"),
                      re.MULTILINE)
    assert len(maturin) == 1 and build and build.group(1) == maturin[0], (maturin, build)
