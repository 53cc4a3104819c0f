"""Where the tests find the module, the program and the data sets (scripts/test.sh sets them)."""
import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATASETS = ROOT.parent / "shared" / "datasets"


@pytest.fixture(scope="session")
def cli():
    return os.environ.get("SLAMKIT_CLI", str(ROOT / "build" / "release" / "bin" / "slamkit"))


@pytest.fixture(scope="session")
def datasets():
    if not DATASETS.exists():
        pytest.skip("no ../shared/datasets beside the repository")
    return DATASETS


@pytest.fixture(scope="session")
def root():
    return ROOT
