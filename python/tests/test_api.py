"""The Python surface: every public name documented and in the stub; errors and shapes."""
import ast
import pathlib

import numpy as np
import pytest

import inbetween

STUB = pathlib.Path(inbetween.__file__).with_name("__init__.pyi")


def stub_names():
    tree = ast.parse(STUB.read_text())
    names, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
            if isinstance(node, ast.ClassDef):
                members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    return names, members


def test_every_public_name_has_a_docstring_and_a_stub():
    names, members = stub_names()
    public = [n for n in inbetween.__all__ if not n.startswith("_")]
    assert public, "the module exports nothing"
    for name in public:
        obj = getattr(inbetween, name)
        assert obj.__doc__ and obj.__doc__.strip(), f"{name} has no docstring"
        assert name in names, f"{name} is missing from {STUB.name}"
        if isinstance(obj, type) and name != "Error":
            for attr in dir(obj):
                if attr.startswith("_") and attr != "__init__":
                    continue
                member = getattr(obj, attr)
                assert member.__doc__ and member.__doc__.strip(), f"{name}.{attr} has no docstring"
                assert attr in members[name], f"{name}.{attr} is missing from the stub"
    # Nothing in the stub that the module lacks.
    for name in names:
        assert hasattr(inbetween, name), f"the stub names {name}, the module has none"


def test_error_is_a_value_error_with_message_place_and_code():
    with pytest.raises(inbetween.Error) as info:
        inbetween.Curve({"type": "catmull-rom", "points": [[0, 0], [1, 2, 3]]})
    e = info.value
    assert isinstance(e, ValueError)
    assert e.code == "WrongArity"
    assert e.where == "curve:/points/1"
    assert str(e) == "curve:/points/1: " + e.message


@pytest.mark.parametrize("call, shape_text", [
    (lambda: inbetween.matrix_from_quat(np.zeros((5, 3))), "(..., 4)"),
    (lambda: inbetween.quat_from_matrix(np.zeros((5, 3))), "(..., 3, 3)"),
    (lambda: inbetween.quat_from_euler("XYZ", np.zeros((2, 4))), "(..., 3)"),
    (lambda: inbetween.quat_from_rotvec(np.zeros(4)), "(..., 3)"),
])
def test_wrong_shapes_are_value_errors_naming_the_shape(call, shape_text):
    with pytest.raises(ValueError, match=r"expected an array of shape " + shape_text.replace("(", r"\(")
                       .replace(")", r"\)").replace(".", r"\.")):
        call()


def test_slerp_counts_must_broadcast():
    with pytest.raises(ValueError, match="expected 1 or 3"):
        inbetween.slerp(np.tile([1.0, 0, 0, 0], (3, 1)), np.tile([1.0, 0, 0, 0], (2, 1)), 0.5)


def test_bad_euler_sequence_is_an_error():
    with pytest.raises(inbetween.Error):
        inbetween.quat_from_euler("XXY", np.zeros(3))
    with pytest.raises(inbetween.Error):
        inbetween.quat_from_euler("XyZ", np.zeros(3))


def test_not_a_rotation_names_its_index():
    m = np.stack([np.eye(3), np.diag([1.0, 1.0, -1.0])])
    with pytest.raises(inbetween.Error) as info:
        inbetween.quat_from_matrix(m)
    assert info.value.where == "/1" and info.value.code == "NotARotation"
