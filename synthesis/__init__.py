"""Optimisation synthesis of lever mechanisms (blocks B1-B5, Peisakh criteria), the built-in
cases and the command line. Uses only the public API of :mod:`assur`."""
