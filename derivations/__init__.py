"""Symbolic layer: derive the paper's formulas, certify them, hand them to the renderer.

Never imported by the runtime package or by ``generated/`` (DESIGN.md, data flow).
"""
