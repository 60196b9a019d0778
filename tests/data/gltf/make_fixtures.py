#!/usr/bin/env python3
# Writes the glTF fixtures of tests/common/scene/test_gltf_*.cpp (the loader of the contract
# (README.md) "Scenes"): small valid files, each showing one rule (valid_fixtures.py), the
# textures' files (texture_fixtures.py), and malformed ones, each broken in one way
# (malformed_fixtures.py). Standard library only; run it from anywhere.
import sys

sys.dont_write_bytecode = True  # leave no __pycache__ among the fixtures

from malformed_fixtures import broken, broken_sparse, lfs_pointers, required_extensions  # noqa: E402
from texture_fixtures import textures  # noqa: E402
from valid_fixtures import (attributes, blender_like, cameras, glb, index_types, interleaved,  # noqa: E402
                            layouts, lights, materials, sparse, transforms)


if __name__ == "__main__":
    transforms()
    index_types()
    interleaved()
    cameras()
    materials()
    lights()
    glb()
    blender_like()
    layouts()
    sparse()
    attributes()
    textures()
    broken()
    broken_sparse()
    required_extensions()
    lfs_pointers()
