"""Four-bar for a prescribed velocity ratio."""
