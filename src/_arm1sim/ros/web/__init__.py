"""gzclient's part: the browser view of a running world (``gzserver --web``), a viser page
(``web_view``) over what it reads of the world two steps at a time (``web_snapshot``).
"""
