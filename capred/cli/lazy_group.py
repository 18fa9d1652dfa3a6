"""`capred` as a click group whose commands are built when they are used.

typer turns every command's signature into click parameters before it runs anything: for capred's twenty-odd
commands and their shared options that is about a quarter of the CPU of `capred --help` (26 ms of 106 ms,
measured on the project's 2-core machine). :func:`lazy_command` builds the same group as
``typer.main.get_command(app)``, but each command (and each command group, such as ``bridge``) is built from
its typer declaration only when click asks for it: `capred shear --help` builds ``shear`` alone, and the
command list of `capred --help` is written from light stand-ins that carry a command's name, its short help
and whether it is hidden, made the way typer makes them.

Where typer's internals differ from what this module expects, :func:`lazy_command` gives typer's own group:
the command line behaves the same, only slower to start.
"""

from __future__ import annotations

import copy
import functools
import inspect

import typer
import typer.core
import typer.main

from .help import HelpGroup


class LazyGroup(HelpGroup):
    """A typer group whose commands are built on first use (:meth:`get_command`).

    ``commands`` holds every command from the start (names in typer's order), as a stand-in until the command
    is first asked for; the command list of the group's help is written from the stand-ins.
    """

    #: command name -> function that builds the real command (emptied as commands are built)
    builders: dict
    _listing = False

    def get_command(self, ctx, cmd_name: str):
        """The command ``cmd_name``, built now if it was not yet (None when the group has no such command).

        Parameters
        ----------
        ctx : click.Context
            The group's context.
        cmd_name : str
            The command's name.

        Returns
        -------
        click.Command or None
        """
        build = None if self._listing else self.__dict__.get("builders", {}).pop(cmd_name, None)
        if build is not None:
            self.commands[cmd_name] = build()
        return self.commands.get(cmd_name)

    def format_commands(self, ctx, formatter) -> None:
        """The command list of the group's help, from the stand-ins (no command is built for it).

        Parameters
        ----------
        ctx : click.Context
            The group's context.
        formatter : click.HelpFormatter
            The formatter written to.
        """
        self._listing = True
        try:
            super().format_commands(ctx, formatter)
        finally:
            self._listing = False


def lazy_command(app: typer.Typer):
    """The click group of ``app`` with its commands built on first use (see the module docstring).

    Parameters
    ----------
    app : typer.Typer
        The application.

    Returns
    -------
    click.Command
        A :class:`LazyGroup`, or typer's own group (``typer.main.get_command(app)``) where the application has
        something this module does not build lazily (shell completion options, a group class of its own, a
        group added without a name) or typer's internals differ.
    """
    if not getattr(app, "_add_completion", True):
        try:
            return _lazy_group(
                typer.main.TyperInfo(app),
                pretty_exceptions_short=app.pretty_exceptions_short,
                rich_markup_mode=app.rich_markup_mode,
                suggest_commands=getattr(app, "suggest_commands", True),
            )
        except _NotLazy:
            pass
    return typer.main.get_command(app)


class _NotLazy(Exception):
    """The application has something that is built the usual way."""


def _lazy_group(group_info, *, pretty_exceptions_short, rich_markup_mode, suggest_commands) -> LazyGroup:
    """As ``typer.main.get_group_from_info``, each command and sub-group left to be built on first use."""
    try:
        get_command_from_info = typer.main.get_command_from_info
        get_group_from_info = typer.main.get_group_from_info
        solve = typer.main.solve_typer_info_defaults
        instance = group_info.typer_instance
        solved = solve(group_info)
    except AttributeError as exc:  # pragma: no cover - other typer versions
        raise _NotLazy from exc
    if solved.cls not in (None, typer.core.TyperGroup, HelpGroup):
        raise _NotLazy
    kw = {"pretty_exceptions_short": pretty_exceptions_short, "rich_markup_mode": rich_markup_mode}
    # typer before 0.20 builds a group without command suggestions (no such keyword)
    group_kw = dict(kw)
    if "suggest_commands" in inspect.signature(get_group_from_info).parameters:
        group_kw["suggest_commands"] = suggest_commands
    stand_ins, builders = {}, {}
    for info in instance.registered_commands:
        if info.callback is None:  # pragma: no cover - typer refuses it when built
            raise _NotLazy
        name = info.name or typer.main.get_command_name(info.callback.__name__)
        helptext = inspect.getdoc(info.callback) if info.help is None else inspect.cleandoc(info.help)
        stand_ins[name] = typer.core.TyperCommand(
            name=name,
            help=helptext,
            short_help=info.short_help,
            hidden=info.hidden,
            deprecated=info.deprecated,
            rich_markup_mode=rich_markup_mode,
        )
        builders[name] = functools.partial(get_command_from_info, info, **kw)
    for sub in instance.registered_groups:
        sub_solved = solve(sub)
        if not sub_solved.name:  # its commands join this group's: built the usual way
            raise _NotLazy
        stand_ins[sub_solved.name] = typer.core.TyperGroup(
            name=sub_solved.name,
            help=sub_solved.help,
            short_help=sub_solved.short_help,
            hidden=sub_solved.hidden,
            deprecated=sub_solved.deprecated,
            rich_markup_mode=rich_markup_mode,
        )
        builders[sub_solved.name] = functools.partial(
            _lazy_or_full, sub, get_group_from_info, suggest_commands=suggest_commands, **kw
        )  # _lazy_or_full hands get_group_from_info only the keywords it takes
    # the group itself (its callback's options, help, settings) as typer builds it, without its commands
    shell = copy.copy(instance)
    shell.registered_commands, shell.registered_groups = [], []
    shell_info = copy.copy(group_info)
    shell_info.typer_instance = shell
    shell_info.cls = LazyGroup
    group = get_group_from_info(shell_info, **group_kw)
    if type(group) is not LazyGroup:  # pragma: no cover - other typer versions
        raise _NotLazy
    group.commands.update(stand_ins)
    group.builders = builders
    return group


def _lazy_or_full(group_info, get_group_from_info, **kw):
    """A sub-group, lazy where it can be, else as typer builds it."""
    try:
        return _lazy_group(group_info, **kw)
    except _NotLazy:
        if "suggest_commands" not in inspect.signature(get_group_from_info).parameters:
            kw.pop("suggest_commands", None)
        return get_group_from_info(group_info, **kw)


__all__ = ["LazyGroup", "lazy_command"]
