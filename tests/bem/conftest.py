"""Shared fixtures of the BEM tests: the configuration's bem section and its two surface
families (config/config.yaml)."""

from pathlib import Path

import pytest
import yaml

from roughcontact.statistics.surface import SpectralMoments

ROOT = Path(__file__).resolve().parents[2]
_BEM = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())["bem"]


@pytest.fixture
def bem_cfg():
    return _BEM


@pytest.fixture
def families():
    return {name: SpectralMoments(**m) for name, m in _BEM["families"].items()}


@pytest.fixture(params=sorted(_BEM["families"]))
def family(request):
    """(name, SpectralMoments) of each family."""
    return request.param, SpectralMoments(**_BEM["families"][request.param])
