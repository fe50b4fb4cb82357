"""What every other package stands on: errors, the clock, literals, observers, the registry, safe output."""
