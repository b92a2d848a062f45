"""What every refusal must look like: one line of plain text (no numpy repr, no newline)."""


def assert_one_line(message):
    assert "\n" not in message and "np." not in message and "float64" not in message, message
