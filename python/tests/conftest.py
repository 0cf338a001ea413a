"""Shared fixtures: the hover trim at 3.5 m that the hover tests start from (as the C++ tests do)."""

import pytest

import thetad


@pytest.fixture(scope="session")
def hover_trim():
    return thetad.Helicopter().trim(altitude=3.5)
