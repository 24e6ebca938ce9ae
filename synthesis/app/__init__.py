"""The application layer: what the commands, the report and the batch check call."""
