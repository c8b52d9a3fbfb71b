"""python -m geodesic_lod: the command geodesic-lod."""
import sys

from .cli import main

sys.exit(main())
