"""Drop-in replacements for other Python libraries' APIs, over lsc:

    from lsc.compat import xarm     # instead of: import xarm
"""
