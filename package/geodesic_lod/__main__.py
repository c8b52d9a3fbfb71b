"""python -m geodesic_lod: the command geodesic-lod."""
import sys

from .command import main

sys.exit(main())
