"""CPU profiles: what one controller family names and numbers (the S7-1200 first)."""
