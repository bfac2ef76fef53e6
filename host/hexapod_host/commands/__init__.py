"""The `hexapod` command line: cli (the parser, exit statuses) and one module per command with register(sub)."""
