"""What a call refuses with."""


def message(fn, *args, **kwargs):
    """The text of the ValueError fn(*args, **kwargs) raises, or "accepted"."""
    try:
        fn(*args, **kwargs)
        return "accepted"
    except ValueError as e:
        return str(e)
