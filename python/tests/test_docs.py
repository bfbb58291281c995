"""The examples in the docstrings run and give what they show."""

import doctest

import pytest

import rbfsurf
from rbfsurf import _api, _checks, _interpolator, _native


@pytest.mark.parametrize("module", [rbfsurf, _api, _checks, _interpolator], ids=lambda m: m.__name__)
def test_module_examples(module):
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


@pytest.mark.parametrize("obj", [_native.Model, _native.Session], ids=lambda o: o.__name__)
def test_native_examples(obj):
    finder = doctest.DocTestFinder()
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    tests = finder.find(obj, obj.__name__, globs={})
    assert sum(len(t.examples) for t in tests) > 0
    for t in tests:
        runner.run(t)
    assert runner.failures == 0
