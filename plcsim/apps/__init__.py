"""What people start: the ``plcsim`` command, the pytest plugin and the live panel."""
