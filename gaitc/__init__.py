"""gaitc: a specification compiler and GR(1) synthesizer for walking soft robots."""

__version__ = "0.1.0"
