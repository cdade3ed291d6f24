"""The 3-D world: vessel models, harbours, and the scene posed at any time."""
