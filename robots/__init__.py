"""Robot builds: one plain-data module per build (lengths 0.1 mm, angles cdeg); hexapod.geometry.load checks them."""
