"""Built-in cases, one subpackage each, every one reproducing its published source."""
