"""Corrections that keep particle distributions regular (transport velocity, ...)."""
